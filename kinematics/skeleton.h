// Skeleton: the immutable joint hierarchy (Pinocchio's Model; the FK results live in
// FkData, see forward_kinematics.h).
//
// Joints are stored parents-first (preorder: parent(j) < j, root 0 has parent -1), so
// the subtree of j is the index range [j, subtree_end(j)). A joint's global transform is
//
//   world_from_joint_j = world_from_joint_parent * T(t_j) * R_rest_j * R_j
//
// with t_j the joint's local translation (its rest offset unless the pose animates it),
// R_rest_j a constant rest rotation (identity for BVH; the ASF axis change for Acclaim),
// and R_j the pose's local rotation. Channels are the file's animation channels, kept
// only so a writer can reproduce the layout; the math never reads Euler angles.
#ifndef MOCAPSOLVE_KINEMATICS_SKELETON_H_
#define MOCAPSOLVE_KINEMATICS_SKELETON_H_

#include <optional>
#include <utility>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/status.h"
#include "kinematics/units.h"

namespace mocapsolve {

enum class Channel { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

struct JointSpec {
  std::string name;
  int parent = -1;                       // Index into the spec list; -1 for the root only.
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // In the parent's frame, file units.
  Eigen::Quaterniond rest_rotation = Eigen::Quaterniond::Identity();
  std::vector<Channel> channels;         // Layout in the source file (may be empty).
  // The axes (0 = x, 1 = y, 2 = z) of the joint's rotation dofs in product order, left
  // to right (R_j = R_axes[0](a) R_axes[1](b) ...), where the format fixes them (ASF:
  // its dof list reversed, since Acclaim applies the first-listed angle first; empty for a
  // bone without rotation dofs). Unset: the rotation channels in listed order (BVH), or
  // all three for a joint without channels.
  std::optional<std::vector<int>> rotation_axes;
  // Limits (radians, lower <= upper, may be infinite) of the Euler angles about
  // rotation_axes, in the same order; empty: unlimited. From the ASF 'limits'.
  std::vector<std::pair<double, double>> rotation_limits;
};

struct EndSite {
  std::string name;  // "<joint>_End" unless the file names it.
  int parent = -1;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // In the parent joint's frame.
};

// Deepest joint chain a skeleton may have. Real ones nest < 40 deep; chain kinematics,
// writers and solvers walk a joint's ancestors, so a file nesting 100,000 joints would
// make them quadratic: every reader refuses it through Skeleton::Create.
constexpr int kMaxSkeletonDepth = 1000;

class Skeleton {
 public:
  Skeleton() = default;

  // Validates the specs (one root at index 0, parent(j) < j, unique non-empty names,
  // finite offsets, unit rest rotations, at most one channel of each kind per joint, at
  // most kMaxSkeletonDepth joints between a joint and the root).
  static Status Create(std::vector<JointSpec> joints, std::vector<EndSite> end_sites,
                       LengthUnit unit, Skeleton* skeleton);

  int num_joints() const { return static_cast<int>(joints_.size()); }
  const JointSpec& joint(int j) const { return joints_[j]; }
  const std::string& name(int j) const { return joints_[j].name; }
  int parent(int j) const { return joints_[j].parent; }
  const Eigen::Vector3d& offset(int j) const { return joints_[j].offset; }
  const Eigen::Quaterniond& rest_rotation(int j) const { return joints_[j].rest_rotation; }
  bool has_rest_rotation(int j) const { return has_rest_rotation_[j]; }
  // One past the last joint of j's subtree (preorder).
  int subtree_end(int j) const { return subtree_end_[j]; }
  bool IsAncestorOrSelf(int ancestor, int j) const {
    return ancestor <= j && j < subtree_end_[ancestor];
  }
  // True if the joint's file channels include positions (so its translation is animated).
  bool has_translation_channels(int j) const { return has_translation_channels_[j]; }
  // The local axes joint j may rotate about, in product order (JointSpec::rotation_axes):
  // an ASF bone's dofs, all three for a BVH joint with rotation channels or a joint built
  // without channels, none for a joint whose channels hold no rotation. Solvers keep
  // each joint's rotation on this set.
  const std::vector<int>& rotation_axes(int j) const { return rotation_axes_[j]; }
  int num_rotation_dofs(int j) const { return static_cast<int>(rotation_axes_[j].size()); }
  // Limits of the angles about rotation_axes(j) (radians), or empty when unlimited.
  const std::vector<std::pair<double, double>>& rotation_limits(int j) const {
    return joints_[j].rotation_limits;
  }
  // Index of the joint, or -1.
  int FindJoint(const std::string& name) const;

  const std::vector<EndSite>& end_sites() const { return end_sites_; }
  const LengthUnit& unit() const { return unit_; }

 private:
  std::vector<JointSpec> joints_;
  std::vector<EndSite> end_sites_;
  std::vector<int> subtree_end_;
  std::vector<bool> has_rest_rotation_;
  std::vector<bool> has_translation_channels_;
  std::vector<std::vector<int>> rotation_axes_;
  LengthUnit unit_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_SKELETON_H_
