// The gauge of a joint one marker alone constrains: the marker world positions do not
// change, at rest the joint puts its marker where it is on average, and the other
// markers and joints are left alone.
#include "problems/marker_solve/lone_joint_gauge.h"

#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

TEST(LoneJointGauge, LeafJointRestsAtItsMeanPoseWithTheSameMarkers) {
  const Skeleton skeleton = MakeDemoSkeleton();
  Motion motion = MakeDemoWalk(skeleton, 40, 60.0);
  const MarkerSet all = MakeSyntheticMarkerSet(skeleton, 3, 4);
  // A leaf joint with markers and a full dof set keeps one of them.
  std::vector<bool> has_child(skeleton.num_joints(), false);
  for (int j = 1; j < skeleton.num_joints(); ++j) has_child[skeleton.parent(j)] = true;
  int leaf = -1;
  for (int m = 0; m < all.num_markers(); ++m) {
    const int j = all.marker(m).attachments[0].joint;
    if (!has_child[j] && skeleton.num_rotation_dofs(j) == 3) leaf = j;
  }
  ASSERT_GE(leaf, 0);
  std::vector<MarkerSpec> specs;
  std::string lone_label;
  for (int m = 0; m < all.num_markers(); ++m) {
    const MarkerSpec& spec = all.marker(m);
    if (spec.attachments[0].joint == leaf) {
      if (!lone_label.empty()) continue;
      lone_label = spec.label;
    }
    specs.push_back(spec);
  }
  MarkerSet markers;
  ASSERT_TRUE(MarkerSet::Create(skeleton, specs, &markers).ok());
  // The lone joint far from its rest pose, about a constant rotation plus a wobble.
  const Eigen::Quaterniond bias = ExpMap(Eigen::Vector3d(1.2, -0.4, 0.7));
  for (int f = 0; f < motion.num_frames(); ++f) {
    motion.frames[f].rotations[leaf] = bias * ExpMap(Eigen::Vector3d(0.1 * std::sin(0.3 * f), 0.05, 0.0));
  }
  const MarkerSet before_markers = markers;
  const Motion before_motion = motion;
  std::vector<std::string> labels;
  ASSERT_TRUE(FixLoneJointGauges(skeleton, &markers, &motion, &labels).ok());
  ASSERT_EQ(labels, std::vector<std::string>{lone_label});
  FkData before(skeleton), after(skeleton);
  const int lone = markers.FindMarker(lone_label);
  const Eigen::Vector3d z = markers.marker(lone).attachments[0].offset;
  Eigen::Vector3d mean_local = Eigen::Vector3d::Zero();
  for (int f = 0; f < motion.num_frames(); ++f) {
    ForwardKinematics(skeleton, before_motion.frames[f], &before);
    ForwardKinematics(skeleton, motion.frames[f], &after);
    for (int m = 0; m < markers.num_markers(); ++m) {
      EXPECT_LT((markers.Position(m, after) - before_markers.Position(m, before)).norm(), 1e-9);
    }
    mean_local += motion.frames[f].rotations[leaf] * z;
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      if (j != leaf) {
        EXPECT_TRUE(motion.frames[f].rotations[j].isApprox(before_motion.frames[f].rotations[j]));
      }
    }
  }
  // At rest the joint puts the marker on the mean of its fitted local positions' direction.
  EXPECT_LT(mean_local.normalized().cross(z.normalized()).norm(), 1e-9);
  EXPECT_GT(mean_local.dot(z), 0.0);
  // Every other marker keeps its offset.
  for (int m = 0; m < markers.num_markers(); ++m) {
    if (markers.label(m) != lone_label) {
      EXPECT_TRUE(markers.marker(m).attachments[0].offset.isApprox(before_markers.marker(m).attachments[0].offset));
    }
  }
}

TEST(LoneJointGauge, Errors) {
  const Skeleton skeleton = MakeDemoSkeleton();
  MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 1, 4);
  Motion empty;
  std::vector<std::string> labels;
  EXPECT_FALSE(FixLoneJointGauges(skeleton, &markers, &empty, &labels).ok());
}

}  // namespace
}  // namespace mocapsolve
