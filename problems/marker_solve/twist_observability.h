// TwistObservability: how strongly the markers below a joint observe its twist about a line
// through it, once the joints below have turned to make up for it.
//
// Joint j turned by theta about u (unit, j's own frame: q_j <- q_j exp(theta u)) moves a marker
// attached below j at world point p by theta a x (p - o_j), a = R_j u, o_j the joint's world
// origin (thesis eq. 2); a joint c below j can take up part of that with its own dofs (columns
// a_k x (p - o_c) for the local axes k of Skeleton::rotation_axes(c)). With J_t the twist's
// column over the rows of every marker whose attachments all lie strictly below j (3 rows
// each, blended attachments by their weights) and J_c the columns of every dof of the joints
// strictly below j, the result is the least-squares residual
//   s = | J_t - J_c J_c^+ J_t |          (skeleton units of marker motion per radian)
// at `pose`: the twist's effect no rotation below can hide. 0 when no marker lies below j, or
// when the joints below can turn freely about the same line (a ball joint at a point on it):
// then only j's own markers decide the twist, and with one of them left it is free.
// Unweighted (every marker row 1; the solve's marker_weight scales it).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_TWIST_OBSERVABILITY_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_TWIST_OBSERVABILITY_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

// visible: one flag per marker, only those rows count (nullptr: every marker).
double TwistObservability(const Skeleton& skeleton, const MarkerSet& markers, const Pose& pose, int joint,
                          const Eigen::Vector3d& axis_in_joint, const std::vector<bool>* visible = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_TWIST_OBSERVABILITY_H_
