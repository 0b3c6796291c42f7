// FloorResidual: keeps one target foot joint above the floor, an extra block of the
// per-frame retarget solve (retarget_frame_solver.h), one-sided:
//
//   r = scale * min(0, y_k(t_root, q) - h)                             1 row, unitless
//
// with y_k the height (world +y) of target joint k's origin from the chain's forward
// kinematics (kinematics/chain_kinematics.h), h the lowest height the joint may take (the
// floor plus the joint's rest clearance above the character's sole, foot_clearance.h) and
// scale = floor_weight / sigma (read through a pointer at each Evaluate, like h). Zero, with
// a zero Jacobian, while the joint is above h: the term only pushes up.
//
// Parameter blocks, in order (as FootPlantResidual's):
//   0:      the root translation t_root, 3 doubles (target skeleton units, world frame);
//   1 + s:  the local rotation q_j of joint j = chain(k)[s] (the ancestors of k and k
//           itself, parents first, starting at the root), 4 doubles (x, y, z, w) on
//           RightQuaternionManifold (R_j <- R_j exp(delta)).
//
// Jacobians (row-major; any may be null), while y_k < h (else zero):
//   d r / d t_root = scale e_y^T (1 x 3);
//   d r / d q_j    = scale e_y^T [o_j - o_k]x R_j * AmbientFromTangent(q_j) / |q_j|  (1 x 4),
// the y row of FootPlantResidual's (zero for q_k itself). At y_k = h exactly the row is
// taken as inactive (the one-sided derivative from above).
//
// The lean DLS kernel has only 3-row point rows; it realizes the same constraint as an
// active set (RetargetFrameSolver): after the frame's solve, each joint under h gets a point
// row toward (x_k, h, z_k) and the frame is solved again.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_FLOOR_RESIDUAL_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_FLOOR_RESIDUAL_H_

#include <vector>

#include <ceres/cost_function.h>

#include "kinematics/chain_kinematics.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

class FloorResidual : public ceres::CostFunction {
 public:
  // The skeleton, lowest height and scale must outlive the residual.
  FloorResidual(const Skeleton* skeleton, int joint, const double* lowest_height, const double* scale);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  const std::vector<int>& joints() const { return chain_.joints; }
  int joint() const { return joint_; }

 private:
  const Skeleton* skeleton_;
  int joint_;
  const double* lowest_height_;
  const double* scale_;
  JointChain chain_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_FLOOR_RESIDUAL_H_
