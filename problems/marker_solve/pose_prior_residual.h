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
// With an axis (set_axis: u, a unit vector in the joint's own frame, and weight_u) the rotation
// prior is anisotropic: its weight about u is weight_u, about the directions normal to u weight:
//   b = q_ref (x) (u, 0)      (a unit 4-vector normal to q_ref: the tangent of q_ref exp(t u))
//   r = 2 [weight I + (weight_u - weight) b b^T] (q - s q_ref)                 4 rows
// since q = q_ref exp(v) gives b . (q - s q_ref) = s u . v / 2 + O(|v|^3): the twist of q about
// u relative to q_ref (a rotation q exp(t u) that leaves a point on the line through the
// joint along u in place). Jacobian d r/d q = 2 [weight I + (weight_u - weight) b b^T] (4 x 4);
// without an axis r and its Jacobian are the isotropic ones above, bit for bit.
//
// The references are read through pointers at each Evaluate, so a frame-by-frame
// solver updates them in place; a rotation prior's weight and axis may be reset between
// solves (set_weight: a frame solver raises a hidden joint's pull toward its mean pose;
// set_axis: the twist of a joint about the line to its one observed marker).
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
  // The weight about axis_in_joint (unit length, the joint's own frame); clear_axis: none.
  void set_axis(const double* axis_in_joint, double axis_weight) {
    for (int i = 0; i < 3; ++i) axis_[i] = axis_in_joint[i];
    axis_weight_ = axis_weight;
    has_axis_ = true;
  }
  void clear_axis() { has_axis_ = false; }
  bool has_axis() const { return has_axis_; }

 private:
  const double* reference_;
  double weight_;
  bool has_axis_ = false;
  double axis_[3] = {0, 0, 0};
  double axis_weight_ = 0.0;
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
