#include "problems/edit_propagation/harmonic_residual.h"

#include <glog/logging.h>

namespace mocapsolve {

HarmonicEdgeResidual::HarmonicEdgeResidual(double kernel) : sqrt_kernel_(std::sqrt(kernel)) {
  CHECK(kernel >= 0.0 && std::isfinite(kernel)) << "kernel " << kernel;
}

bool HarmonicEdgeResidual::Evaluate(double const* const* parameters, double* residuals,
                                    double** jacobians) const {
  residuals[0] = sqrt_kernel_ * (parameters[0][0] - parameters[1][0]);
  if (jacobians != nullptr) {
    if (jacobians[0] != nullptr) jacobians[0][0] = sqrt_kernel_;
    if (jacobians[1] != nullptr) jacobians[1][0] = -sqrt_kernel_;
  }
  return true;
}

}  // namespace mocapsolve
