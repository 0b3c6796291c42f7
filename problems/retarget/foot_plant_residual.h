// FootPlantResidual: keeps one target foot joint where its contact began (issue 11 item
// 3), an extra block of the per-frame retarget solve (retarget_frame_solver.h).
//
//   r = scale * (o_k(t_root, q) - a)                                   3 rows, unitless
//
// with o_k the world origin of target joint k from the chain's forward kinematics
// (kinematics/chain_kinematics.h), a the anchor (the joint's position at the first frame
// of the contact, target units) and scale = plant_weight / sigma while the joint is
// planted, 0 otherwise (read through a pointer at each Evaluate, like the anchor, so a
// solver keeps one Problem and switches the term per frame).
//
// Parameter blocks, in order (as TrackedVertexResidual's):
//   0:      the root translation t_root, 3 doubles (target skeleton units, world frame);
//   1 + s:  the local rotation q_j of joint j = chain(k)[s] (the ancestors of k and k
//           itself, parents first, starting at the root), 4 doubles (x, y, z, w) on
//           RightQuaternionManifold (R_j <- R_j exp(delta)).
//
// Jacobians (row-major; any may be null):
//   d r / d t_root = scale I (3 x 3);
//   d r / d q_j    = scale [o_j - o_k]x R_j * AmbientFromTangent(q_j) / |q_j|   (3 x 4),
// zero for q_k itself (a joint's rotation does not move its origin). This is the
// position row of TrackedVertexResidual for a vertex of weight 1 on joint k at zero
// offset, which is how the lean DLS kernel stacks it (one more row of its kernel).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_FOOT_PLANT_RESIDUAL_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_FOOT_PLANT_RESIDUAL_H_

#include <vector>

#include <ceres/cost_function.h>
#include <Eigen/Core>

#include "kinematics/chain_kinematics.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

// The ancestors of `joint` and the joint itself, ascending (starting at the root).
std::vector<int> AncestorChain(const Skeleton& skeleton, int joint);

class FootPlantResidual : public ceres::CostFunction {
 public:
  // The skeleton, anchor and scale must outlive the residual.
  FootPlantResidual(const Skeleton* skeleton, int joint, const Eigen::Vector3d* anchor, const double* scale);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  const std::vector<int>& joints() const { return chain_.joints; }
  int joint() const { return joint_; }

 private:
  const Skeleton* skeleton_;
  int joint_;
  const Eigen::Vector3d* anchor_;
  const double* scale_;
  JointChain chain_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_FOOT_PLANT_RESIDUAL_H_
