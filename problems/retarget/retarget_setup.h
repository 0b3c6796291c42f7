// Retarget setup (thesis 4.3.1-4.3.5): which target vertex tracks which source vertex,
// by position or by normal, and what it tracks in each frame.
//
// Tracked vertices: the source mesh is subsampled (vertex_subsampling.h, in its bind
// pose) and each sample s is mapped to the nearest target vertex k(s) in the common rest
// frame (mesh_mapping.h). The correspondence comes from the meshes only: the skeletons
// may differ in joint count, names and hierarchy.
//
// Goals, per frame f (target mesh units, target world frame): with the source's skinned
// position p_s and LBS normal n_s (eqs. 5-6, not renormalized) at frame f,
//   position goal  g = o_t + (h_t / h_s) F_t^T F_s (p_s - o_s)
//   normal goal    m = F_t^T F_s n_s,  n_s = sum_b w_b rot(S_b) y   (LBS, eq. 6)
// where o, h, F are the characters' rest frames (CharacterFrame of the bind-pose meshes:
// feet-level origin, height, facing; mesh_mapping.h), so the source's motion is turned
// to face the way the target faces, and y is either the source vertex's rest normal
// (eq. 16 as written) or, by default, the target vertex's rest normal brought into the
// source's bind space (normal transfer: the target surface turns as the source surface
// turns). Nearest vertices of two different meshes often face quite different ways
// (measured ~50-65 degrees on average between the glTF characters), which eq. 16 would
// try to force onto the target even in the rest pose.
// So positions are brought into the target's scale by the height ratio about the rest
// frames' origins: the source's global path (its root's travel) is scaled by the same
// ratio. The target root translation is an unknown of each frame's solve, held in place
// by the position-tracked vertices (warm start: the previous frame; frame 0 re-centred
// on the goals, see retarget_clip.h).
//
// Normalization (4.3.3): sigma = the standard deviation of all position goals over the
// clip, sqrt(sum |g - mean g|^2 / (3 N)), computed once; position residuals are divided
// by sigma so they are on the scale of the (unit) normals.
//
// Blend mask (4.3.4): B_s = 0 (track the position) when the target vertex's cumulative
// skin weight (4.3.5) on the subtrees of the "position joints" is >= 0.5, else 1 (track
// the normal). Position joints: given by name (a blend-mask file), or automatically
// every target joint whose name contains hand, foot, toe or head (case-insensitive),
// i.e. the end effectors that touch the world. If no joint matches (CesiumMan's
// "leg_joint_L_5"), the end of every chain is used instead: each leaf joint's nearest
// ancestor-or-self that dominates some vertex (noted in RetargetSetup::notes).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_SETUP_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_SETUP_H_

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/forward_kinematics.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"
#include "problems/retarget/mesh_mapping.h"
#include "problems/retarget/vertex_subsampling.h"

namespace mocapsolve {

struct RetargetSetupOptions {
  SubsampleOptions subsample;
  // Rotations from each mesh's bind space into its world (Y up), e.g. from
  // WorldFromBindRotation: glTF bind spaces may be Z up (CesiumMan) or face -Z (Soldier)
  // while the animated world is Y up.
  Eigen::Matrix3d source_world_from_bind = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d target_world_from_bind = Eigen::Matrix3d::Identity();
  // Each character's left in its world (role_sides.h), which signs its facing
  // (ComputeCharacterFrame); zero: the lowest vertices sign it.
  Eigen::Vector3d source_left = Eigen::Vector3d::Zero();
  Eigen::Vector3d target_left = Eigen::Vector3d::Zero();
  // Explicit position joints (target joint names); empty: automatic from the patterns.
  std::vector<std::string> position_joints;
  std::vector<std::string> position_name_patterns = {"hand", "foot", "toe", "head"};
  double position_weight_threshold = 0.5;
  // Normals in the mapping's distance (heights per unit normal difference; 0 = eq. 11
  // as written). See MapToNearestVertices. With transferred normals the mapping's normal
  // mismatch no longer matters and 0 measured best on Soldier -> Xbot (vertex error
  // 0.0195 vs 0.0243 of the height at 0.05), about even on CesiumMan -> RiggedFigure.
  double mapping_normal_weight = 0.0;
  // Normal goals: true = transfer (the target vertex's own rest normal, carried by the
  // source vertex's skinning rotation), false = the source's skinned normal (eq. 16 as
  // written). Identical when the rest normals agree (same mesh, scaled copy).
  bool transfer_normals = true;
  // Per source vertex, its body part (humanoid_roles.h BodyParts of its heaviest joint), -1
  // none; empty: no per-part quota (vertex_subsampling.h step 4).
  std::vector<int> source_parts;
  // The source mesh is the target's own mesh bound to the source skeleton (skeleton_binding.h:
  // the same vertices in the same order): each sample tracks its own vertex on the target,
  // not the nearest one in the common frame (where the two skeletons' proportions differ, the
  // nearest vertex to a sample on the source's hand can lie on the target's hip).
  bool same_vertices = false;
};

struct TrackedVertex {
  int source_vertex = -1;
  int target_vertex = -1;
  bool track_position = false;  // B = 0; otherwise the normal is tracked (B = 1).
  // The rest normal the source's skinning carries to make the normal goal, in the source's
  // bind space: the source vertex's own, or (transfer_normals) the target vertex's.
  Eigen::Vector3d rest_normal = Eigen::Vector3d::Zero();
};

struct RetargetSetup {
  std::vector<TrackedVertex> tracked;
  CharacterFrame source_frame, target_frame;
  double scale = 1.0;               // h_t / h_s.
  std::vector<int> position_joints;  // Target joints whose subtrees are position-tracked.
  std::vector<std::string> notes;    // Decisions worth reporting (fallbacks).
};

// The mesh as modelled (its bind pose), rotated into the world: world_from_bind times the
// rest positions and unit rest normals, 3 x #V each. Subsampling, mapping and the rest
// frames all use this pose, so both characters should be bound in similar poses (T or A).
void BindPoseMesh(const SkinnedMesh& mesh, const Eigen::Matrix3d& world_from_bind,
                  Eigen::Matrix3Xd* positions, Eigen::Matrix3Xd* normals);

// How the bind space sits in the animated world, from the skeleton's root joint: its
// world rotation at `world_pose` (e.g. a glTF file's node rest pose, which carries the
// nodes above the skeleton, such as CesiumMan's Z_UP) times the inverse of its world
// rotation at `bind_pose` (the pose of the inverse bind matrices). Only the root is
// used, so a rest pose that differs from the bind pose in the limbs (Soldier) does not
// disturb it; a yaw of the root between the two poses is removed later by the facing
// alignment (mesh_mapping.h).
Eigen::Matrix3d WorldFromBindRotation(const Skeleton& skeleton, const Pose& bind_pose,
                                      const Pose& world_pose);

// Errors: a mesh without normals or vertices, an unknown position joint name.
Status BuildRetargetSetup(const SkinnedMesh& source_mesh, const Skeleton& target_skeleton, const SkinnedMesh& target_mesh,
                          const RetargetSetupOptions& options, RetargetSetup* setup);

// Per-frame goals of the tracked vertices (3 x #tracked each) and sigma.
struct RetargetGoals {
  std::vector<Eigen::Matrix3Xd> positions;
  std::vector<Eigen::Matrix3Xd> normals;
  double sigma = 1.0;
};

void ComputeRetargetGoals(const RetargetSetup& setup, const Skeleton& source_skeleton,
                          const SkinnedMesh& source_mesh, const Motion& source_motion,
                          RetargetGoals* goals);

// The same goals one frame at a time, for clips too long to hold every frame's goals
// (2 x 3 x #tracked doubles per frame): Frame(pose) gives exactly ComputeRetargetGoals'
// columns for a frame of that pose, and Sigma(motion) exactly its sigma, from two passes
// over the frames (the sum, then the squares about the mean) without storing them.
// Keeps references to its arguments; one per thread.
class RetargetGoalFrames {
 public:
  RetargetGoalFrames(const RetargetSetup& setup, const Skeleton& source_skeleton, const SkinnedMesh& source_mesh);
  // normals may be null (positions only).
  void Frame(const Pose& source_pose, Eigen::Matrix3Xd* positions, Eigen::Matrix3Xd* normals);
  // false (sigma untouched) when a frame's position goals are not all finite.
  bool Sigma(const Motion& source_motion, double* sigma);

 private:
  const RetargetSetup& setup_;
  const Skeleton& skeleton_;
  const SkinnedMesh& mesh_;
  Eigen::Matrix3d turn_;  // Target world from source world: face the way the target faces.
  FkData fk_;
  std::vector<Eigen::Isometry3d> transforms_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_SETUP_H_
