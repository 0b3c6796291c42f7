// MarkerResidual: one observed marker at one frame (thesis eq. 9 as the model).
//
//   r = weight * (x_m(t_root, q_j for j in chain(m)) - observed)          3 rows, length units
//
// with x_m = sum_k w_mk world_from_joint_{j_mk} z_mk (kinematics/marker_set.h) and chain(m)
// = MarkerSet::InfluencingJoints(m): the ancestors of the marker's joints, parents
// first (always starting at the root, joint 0).
//
// Parameter blocks, in order:
//   0:      the root translation t_root, 3 doubles (skeleton length units, world frame);
//   1 + s:  the local rotation q_j of joint j = chain(m)[s], 4 doubles in Eigen order
//           (x, y, z, w) on RightQuaternionManifold (R_j <- R_j exp(delta)).
// Non-root joints keep their skeleton offsets as translations.
//
// Jacobians (row-major; any may be null, and `jacobians` itself may be null):
//   d r / d t_root = weight * I (3 x 3);
//   d r / d q_j    = weight * J_tan * AmbientFromTangent(q_j) (3 x 4), where
//     J_tan = sum_{k: j_mk in subtree(j)} w_mk [o_j - p_mk]x R_j      (DESIGN.md),
//   exact also for markers blended over bones of different branches. q is normalized
//   before use, so the residual is defined for any non-zero 4-vector.
//
// The observation is read through a pointer at each Evaluate, so a solver can move one
// Problem from frame to frame by updating the observations in place.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_RESIDUAL_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_RESIDUAL_H_

#include <vector>

#include <ceres/cost_function.h>
#include <Eigen/Core>

#include "kinematics/chain_kinematics.h"
#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

class MarkerResidual : public ceres::CostFunction {
 public:
  // The skeleton, marker set and observation must outlive the residual.
  MarkerResidual(const Skeleton* skeleton, const MarkerSet* marker_set, int marker,
                 const Eigen::Vector3d* observed, double weight);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  // chain(m): the joint of each rotation parameter block 1..n.
  const std::vector<int>& joints() const { return chain_.joints; }
  int marker() const { return marker_; }

 private:
  const Skeleton* skeleton_;
  const MarkerSet* marker_set_;
  int marker_;
  const Eigen::Vector3d* observed_;
  double weight_;
  JointChain chain_;              // Joint of each rotation block.
  std::vector<int> attachment_slot_;  // Slot of each attachment's joint.
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_RESIDUAL_H_
