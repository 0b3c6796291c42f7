// Pose priors: pull a rotation or a translation toward a reference (the previous frame's
// solution, or the rest pose's identity, in per-frame solving; a neighbouring frame in
// whole-clip smoothness).
//
// RotationPriorResidual, one parameter block q (4, Eigen order, RightQuaternionManifold):
//   r = 2 weight (q - s q_ref),  s = sign(q . q_ref)                         4 rows
// the chordal distance: |r| = 2 weight |q - s q_ref| = 4 weight sin(theta / 4) ~ weight *
// theta for the angle theta between the two rotations (radians). Jacobian d r/d q = 2
// weight I (4 x 4), exact away from the measure-zero set where s flips.
//
// TranslationPriorResidual, one parameter block t (3):
//   r = weight (t - t_ref)        3 rows, Jacobian weight I (3 x 3)
//
// The references are read through pointers at each Evaluate, so a frame-by-frame
// solver updates them in place; a rotation prior's weight may be reset between solves
// (set_weight: a frame solver raises a hidden joint's pull toward its mean pose).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_POSE_PRIOR_RESIDUAL_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_POSE_PRIOR_RESIDUAL_H_

#include <ceres/sized_cost_function.h>

namespace mocapsolve {

class RotationPriorResidual : public ceres::SizedCostFunction<4, 4> {
 public:
  RotationPriorResidual(const double* reference_xyzw, double weight)
      : reference_(reference_xyzw), weight_(weight) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  void set_weight(double weight) { weight_ = weight; }
  double weight() const { return weight_; }

 private:
  const double* reference_;
  double weight_;
};

class TranslationPriorResidual : public ceres::SizedCostFunction<3, 3> {
 public:
  TranslationPriorResidual(const double* reference, double weight)
      : reference_(reference), weight_(weight) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const double* reference_;
  double weight_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_POSE_PRIOR_RESIDUAL_H_
