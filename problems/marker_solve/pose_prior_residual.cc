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
