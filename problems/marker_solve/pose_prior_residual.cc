#include "problems/marker_solve/pose_prior_residual.h"

namespace mocapsolve {

bool RotationPriorResidual::Evaluate(double const* const* parameters, double* residuals,
                                     double** jacobians) const {
  const double* q = parameters[0];
  double dot = 0.0;
  for (int i = 0; i < 4; ++i) dot += q[i] * reference_[i];
  const double sign = dot < 0.0 ? -1.0 : 1.0;
  for (int i = 0; i < 4; ++i) residuals[i] = 2.0 * weight_ * (q[i] - sign * reference_[i]);
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    for (int i = 0; i < 16; ++i) jacobians[0][i] = (i % 5 == 0) ? 2.0 * weight_ : 0.0;
  }
  if (!has_axis_) return true;
  // b = q_ref (x) (u, 0), Eigen order (x, y, z, w); q_ref = (x, y, z, w) = (e, w).
  const double* e = reference_;
  const double* u = axis_;
  const double b[4] = {e[3] * u[0] + e[1] * u[2] - e[2] * u[1],
                       e[3] * u[1] + e[2] * u[0] - e[0] * u[2],
                       e[3] * u[2] + e[0] * u[1] - e[1] * u[0],
                       -(e[0] * u[0] + e[1] * u[1] + e[2] * u[2])};
  double along = 0.0;
  for (int i = 0; i < 4; ++i) along += b[i] * (q[i] - sign * reference_[i]);
  const double extra = 2.0 * (axis_weight_ - weight_);
  for (int i = 0; i < 4; ++i) residuals[i] += extra * along * b[i];
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    for (int i = 0; i < 4; ++i) {
      for (int k = 0; k < 4; ++k) jacobians[0][4 * i + k] += extra * b[i] * b[k];
    }
  }
  return true;
}

bool TranslationPriorResidual::Evaluate(double const* const* parameters, double* residuals,
                                        double** jacobians) const {
  for (int i = 0; i < 3; ++i) residuals[i] = weight_ * (parameters[0][i] - reference_[i]);
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    for (int i = 0; i < 9; ++i) jacobians[0][i] = (i % 4 == 0) ? weight_ : 0.0;
  }
  return true;
}

}  // namespace mocapsolve
