#include "problems/marker_solve/joint_limit_residual.h"

#include <Eigen/Geometry>

#include "kinematics/rotation.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {

JointLimitResidual::JointLimitResidual(std::vector<int> axes,
                                       std::vector<std::pair<double, double>> limits,
                                       double weight)
    : axes_(std::move(axes)), limits_(std::move(limits)), weight_(weight) {
  set_num_residuals(static_cast<int>(axes_.size()));
  mutable_parameter_block_sizes()->push_back(4);
}

bool JointLimitResidual::Evaluate(double const* const* parameters, double* residuals,
                                  double** jacobians) const {
  const int k = static_cast<int>(axes_.size());
  Eigen::Vector4d q = Eigen::Map<const Eigen::Vector4d>(parameters[0]);
  const double norm = q.norm();
  if (!(norm > 0.0)) return false;
  q /= norm;
  double angles[3];
  Eigen::Matrix<double, Eigen::Dynamic, 3> rate;
  AnglesAboutAxes(Eigen::Quaterniond(q), axes_, angles, jacobians != nullptr ? &rate : nullptr);
  double slope[3];
  for (int i = 0; i < k; ++i) {
    const double above = angles[i] - limits_[i].second, below = angles[i] - limits_[i].first;
    residuals[i] = weight_ * (above > 0.0 ? above : below < 0.0 ? below : 0.0);
    slope[i] = (above > 0.0 || below < 0.0) ? weight_ : 0.0;
  }
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    const Eigen::Matrix<double, 3, 4> ambient = AmbientFromTangent(q.data()) / norm;
    for (int i = 0; i < k; ++i) {
      const Eigen::RowVector4d row = slope[i] * rate.row(i) * ambient;
      for (int c = 0; c < 4; ++c) jacobians[0][i * 4 + c] = row[c];
    }
  }
  return true;
}

}  // namespace mocapsolve
