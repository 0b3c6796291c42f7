// MeasureRetargetQuality: how good a retargeted clip is, measured on the two skeletons'
// motions and the tracking set-up, never on the solve's own residual (a low vertex error
// can hide a wrong skeleton: a character tracked by four hand vertices has one).
//
// Limb directions. The eight limbs (left/right upper arm, forearm, thigh, shin; the target's
// roles of humanoid_roles.h and the source joints the joint map links to them, else the
// source's own roles) point from the role's joint to
// the next role's (upper arm -> forearm -> hand, thigh -> shin -> foot). Per frame f and
// limb l, u_s(l, f) on the source (its motion as retargeted: up axis turned to +y) and
// u_t(l, f) on the result, unit vectors in their worlds. One constant rotation R for all
// limbs and frames absorbs what differs by convention (the source's facing, a rest-pose
// tilt): R maximizes sum <u_t, R u_s> (Wahba's problem, solved by the SVD of
// sum u_t u_s^T with the determinant fixed to +1, Kabsch). The error of a sample is the
// angle between u_t and R u_s; per limb its mean and 95th percentile, over all limbs the
// mean of the limbs' means and the 95th percentile of all samples (degrees). R's angle is
// reported (alignment_deg) so that a tilted result shows.
//
// Torso orientation (pelvis, chest): the limb directions cannot see a pelvis turned about
// its own joint (RobotExpressive's torso box rides on its pelvis-role joint `Body`). Both
// rest poses are taken to stand upright: the references are the target's bind pose in its
// world and the source's upright pose (skeleton_binding.h's upright_world and
// upright_positions: its start pose stood up and turned by the pelvis's rest correction,
// pelvis_rest_correction.h). Pelvis: with W the pelvis role joint's world rotations of a
// frame and B the references' (source s, target t), each side's rotation away from its
// reference D_s = W_s B_s^-1, D_t = W_t B_t^-1 (world frame); the frame's error is the angle
// of D_s^-1 D_t. Chest: its lean, from joint positions (a joint's own rotation can be
// invisible: CMU's thorax has its neck and clavicles starting at one point, and that of a
// chest joint carrying no vertex is free): the direction d from the chest role joint to the
// neck role joint on each side (from the spine_1 role joint where the chest's starts at the
// neck on either side: CMU's BVH Chest2 and lowerneck), d0 the references'; with Q the minimal rotation taking d0_s
// to d0_t (the rigs' designs), the frame's error is the angle between Q d_s and d_t. A
// target carried tilted (or, for the pelvis, twisted) against the source shows whatever the
// tracking residual. Mean and 95th percentile over frames, degrees; NaN without an upright
// pose (a source with its own mesh) or without the roles on both sides.
//
// Foot skate of planted feet: the mean horizontal speed of the target's foot joints over
// the frame pairs where the source's are in contact (retarget_character.h's plant
// skating, cm/s), copied in.
//
// Ground penetration: the floor is y = 0 of the result's world (the retarget keeps the
// source's floor, turned to +y and scaled). Each target foot and toes role joint has its
// rest clearance c_j (its height above the lowest joint or vertex of the target in its rest
// pose); it is under the floor at frame f by max(0, c_j - y_j(f)). Reported: the largest
// over joints and frames and the share of frames with any > 1 cm.
//
// Self joint error: when the source skeleton is the target's own (own_skeleton.h) the joint
// positions of the result against k times the source's (k: the own scale), mean and max
// over joints and frames, cm. NaN otherwise.
//
// Coverage: every tracked vertex (retarget_setup.h) counted on the body part of its target
// vertex's heaviest joint; a joint's part is the role of its nearest ancestor (itself
// included) that plays one (pelvis, spine_1, ..., left_thigh, ...). A limb's direction runs
// from its joint to the next role's (HumanoidLimbs), so its tracked vertices are those of its
// own part and of the part at its end (a forearm without mesh is placed by its hand's). A
// limb tracked by few vertices is not tracked: its rotation is the prior's, whatever the
// residual says.
//
// Lengths in cm when the target's unit is known, else target units. Non-humanoids (no
// roles on either side): limb figures NaN, limb_count 0.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_QUALITY_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_QUALITY_H_

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "problems/retarget/joint_map.h"
#include "problems/retarget/retarget_setup.h"

namespace mocapsolve {

struct LimbDirectionError {
  std::string limb;  // "left_upper_arm", ...
  double mean_deg = 0.0, p95_deg = 0.0;
  int tracked_vertices = 0;  // On the limb's body part and the part at its end.
};

struct RetargetQuality {
  std::vector<LimbDirectionError> limbs;  // The limbs found on both sides.
  double limb_mean_deg = 0.0;             // Mean of the limbs' means (NaN: no limbs).
  double limb_p95_deg = 0.0;              // 95th percentile of all samples (NaN: no limbs).
  double alignment_deg = 0.0;             // Angle of the constant rotation R.
  double pelvis_orientation_mean_deg = 0.0;  // Torso orientation (NaN: not measured).
  double pelvis_orientation_p95_deg = 0.0;
  double chest_orientation_mean_deg = 0.0;  // The chest's lean (chest -> neck).
  double chest_orientation_p95_deg = 0.0;
  double foot_skate_cm_s = 0.0;           // Planted feet (0: no contacts).
  double penetration_cm = 0.0;            // Deepest foot joint under the floor.
  double penetration_frame_share = 0.0;   // Frames with a foot joint > 1 cm under it.
  double self_joint_error_mean_cm = 0.0;  // NaN unless the source is the target's skeleton.
  double self_joint_error_max_cm = 0.0;
  std::vector<std::pair<std::string, int>> coverage;  // (body part, tracked vertices), role order.
  int min_limb_vertices = 0;  // Fewest tracked vertices on a limb (the 8 limbs; 0 when none).
  std::string least_covered_limb;
};

struct RetargetQualityInputs {
  const Skeleton* source = nullptr;
  const Motion* source_motion = nullptr;  // As retargeted (up axis turned).
  const Skeleton* target = nullptr;
  const Motion* result = nullptr;
  const SkinnedMesh* target_mesh = nullptr;
  Pose target_rest;                       // The target's rest (world) pose; empty = RestPose.
  // Torso orientation: the source's upright world rotations (per source joint; nullptr = not
  // measured), the target's bind pose and the rotation taking its bind world to its world.
  const std::vector<Eigen::Quaterniond>* source_upright = nullptr;
  const Vector3dVector* source_upright_positions = nullptr;  // With source_upright.
  Pose target_bind;
  Eigen::Matrix3d target_world_from_bind = Eigen::Matrix3d::Identity();
  const JointMap* joint_map = nullptr;
  const RetargetSetup* setup = nullptr;  // Coverage; nullptr = not tracked (own skeleton).
  double height_ratio = 1.0;             // Target units per source unit.
  bool own_skeleton = false;
  double own_scale = 1.0;
  double foot_skate_cm_s = 0.0;
};

RetargetQuality MeasureRetargetQuality(const RetargetQualityInputs& inputs);

// The target's foot and toes role joints (the joint map's links, else the target's own
// roles; each once): the joints the penetration measure and the floor term take.
std::vector<int> TargetFootJoints(const JointMap& map);

// The eight limbs: (role, next role), arms first.
const std::vector<std::pair<std::string, std::string>>& HumanoidLimbs();

// The joints of each limb found on both sides, as the limb measure takes them: the target's
// role joints (the joint map's links, else the target's own roles) and the source joints
// mapped to them (else the map's or the source's own roles). HumanoidLimbs order.
struct MappedLimb {
  std::string limb;  // The first role's name ("left_upper_arm", ...).
  int source_from = -1, source_to = -1, target_from = -1, target_to = -1;
};
std::vector<MappedLimb> MappedLimbs(const JointMap& map);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_QUALITY_H_
