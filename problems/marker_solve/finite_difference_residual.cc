#include "problems/marker_solve/finite_difference_residual.h"

#include <cstddef>

namespace mocapsolve {

FiniteDifferenceResidual::FiniteDifferenceResidual(SmoothnessOrder order, bool quaternion,
                                                   double weight)
    : coefficients_(order == SmoothnessOrder::kVelocity ? std::vector<double>{-1.0, 1.0}
                                                        : std::vector<double>{1.0, -2.0, 1.0}),
      quaternion_(quaternion), size_(quaternion ? 4 : 3),
      scaled_weight_((quaternion ? 2.0 : 1.0) * weight) {
  set_num_residuals(size_);
  for (std::size_t i = 0; i < coefficients_.size(); ++i) mutable_parameter_block_sizes()->push_back(size_);
}

bool FiniteDifferenceResidual::Evaluate(double const* const* parameters, double* residuals,
                                        double** jacobians) const {
  const int n = static_cast<int>(coefficients_.size());
  const double* last = parameters[n - 1];
  for (int k = 0; k < size_; ++k) residuals[k] = 0.0;
  for (int i = 0; i < n; ++i) {
    double sign = 1.0;
    if (quaternion_) {
      double dot = 0.0;
      for (int k = 0; k < 4; ++k) dot += parameters[i][k] * last[k];
      sign = dot < 0.0 ? -1.0 : 1.0;
    }
    const double factor = scaled_weight_ * coefficients_[i] * sign;
    for (int k = 0; k < size_; ++k) residuals[k] += factor * parameters[i][k];
    if (jacobians != nullptr && jacobians[i] != nullptr) {
      for (int k = 0; k < size_ * size_; ++k) jacobians[i][k] = 0.0;
      for (int k = 0; k < size_; ++k) jacobians[i][k * size_ + k] = factor;
    }
  }
  return true;
}

}  // namespace mocapsolve
