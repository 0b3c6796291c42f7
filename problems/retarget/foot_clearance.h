// FootRestClearances: how high each foot joint stands above the character's sole in its rest
// pose, the height under which the joint is in the floor (retarget_quality.h's penetration,
// floor_residual.h's lowest height).
//
// For joints k (target skeleton indices), c_k = y_k(rest) - min(lowest joint y, lowest
// skinned vertex y) in the rest pose (world, +y up; the mesh is optional), in skeleton units.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_FOOT_CLEARANCE_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_FOOT_CLEARANCE_H_

#include <vector>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"

namespace mocapsolve {

// `mesh` may be null (joints only).
std::vector<double> FootRestClearances(const Skeleton& skeleton, const std::vector<int>& joints, const Pose& rest,
                                       const SkinnedMesh* mesh);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_FOOT_CLEARANCE_H_
