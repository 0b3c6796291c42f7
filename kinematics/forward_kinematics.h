// Forward kinematics (thesis Algorithm 1): local translations and rotations to global
// joint frames, parents first.
//
//   world_rotation_j = world_rotation_parent * R_rest_j * R_j
//   world_position_j = world_position_parent + world_rotation_parent * t_j
//
// The root's parent frame is the world. FkData is the per-thread workspace (Pinocchio's
// Data): allocate it once per skeleton with FkData(skeleton) and reuse it every frame.
#ifndef MOCAPSOLVE_KINEMATICS_FORWARD_KINEMATICS_H_
#define MOCAPSOLVE_KINEMATICS_FORWARD_KINEMATICS_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

struct FkData {
  FkData() = default;
  explicit FkData(const Skeleton& skeleton)
      : world_rotations(skeleton.num_joints()), world_positions(skeleton.num_joints()) {}

  QuaternionVector world_rotations;  // #J, frame of joint j in the world.
  Vector3dVector world_positions;    // #J, origin of joint j in the world (file units).
};

// Requires pose sizes == skeleton.num_joints() and a sized FkData (DCHECKed).
void ForwardKinematics(const Skeleton& skeleton, const Pose& pose, FkData* data);

// World positions of the skeleton's end sites, in end_sites() order.
Vector3dVector EndSitePositions(const Skeleton& skeleton, const FkData& data);

// #frames x #J world joint positions for a whole clip.
std::vector<Vector3dVector> ClipJointPositions(const Skeleton& skeleton, const Motion& motion);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_FORWARD_KINEMATICS_H_
