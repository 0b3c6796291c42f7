// JointLimitResidual: a soft limit on a joint's Euler angles (ASF 'limits').
//
// With t = AnglesAboutAxes(q, axes) (kinematics/rotation.h; the joint's dof angles in
// product order, radians) and limits [l_i, u_i]:
//   r_i = weight * (max(0, t_i - u_i) + min(0, t_i - l_i))        k rows (k = #axes)
// zero inside the limits, growing linearly outside (a hinge; LM copes with the kink).
//
// Parameter block: the joint's local rotation q, 4 doubles (x, y, z, w), on its rotation
// manifold. Jacobian (k x 4, row-major): weight * [t_i outside] * (d t / d delta) *
// AmbientFromTangent(q) / |q|, where d t / d delta is the angles' rate per local
// increment (singular only at gimbal lock of a 3-axis joint).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_JOINT_LIMIT_RESIDUAL_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_JOINT_LIMIT_RESIDUAL_H_

#include <utility>
#include <vector>

#include <ceres/cost_function.h>

namespace mocapsolve {

class JointLimitResidual : public ceres::CostFunction {
 public:
  JointLimitResidual(std::vector<int> axes, std::vector<std::pair<double, double>> limits,
                     double weight);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  std::vector<int> axes_;
  std::vector<std::pair<double, double>> limits_;
  double weight_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_JOINT_LIMIT_RESIDUAL_H_
