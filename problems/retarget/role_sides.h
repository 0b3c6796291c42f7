// LeftOfCharacter: which way is the character's left in its world, from its humanoid roles
// (humanoid_roles.h: sides told by the rest geometry or the names), for the facing of the
// mesh mapping's character frame (mesh_mapping.h), whose mesh-only estimate (the major
// horizontal axis, signed by where the lowest vertices lie) can come out turned by 180
// degrees for a bind pose other than a T-pose with feet forward.
//
//   left = mean of the vertices on left-side parts - mean of those on right-side parts
//
// a vertex's part being its heaviest joint's nearest ancestor (itself included) that plays
// a role ("left_thigh", "right_hand", ...); positions are world_from_bind times the bind
// positions. Zero when the roles have no side or no vertex lies on either side.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_ROLE_SIDES_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_ROLE_SIDES_H_

#include <Eigen/Core>

#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "problems/retarget/humanoid_roles.h"

namespace mocapsolve {

Eigen::Vector3d LeftOfCharacter(const Skeleton& skeleton, const SkinnedMesh& mesh, const HumanoidRoles& roles,
                                const Eigen::Matrix3d& world_from_bind);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_ROLE_SIDES_H_
