#include "problems/retarget/floor_residual.h"

#include <glog/logging.h>

#include "kinematics/rotation.h"
#include "problems/retarget/foot_plant_residual.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

constexpr int kMaxChain = 128;

}  // namespace

FloorResidual::FloorResidual(const Skeleton* skeleton, int joint, const double* lowest_height, const double* scale)
    : skeleton_(skeleton), joint_(joint), lowest_height_(lowest_height), scale_(scale),
      chain_(*skeleton, AncestorChain(*skeleton, joint)) {
  CHECK_LE(chain_.size(), kMaxChain) << "skeleton deeper than supported";
  set_num_residuals(1);
  mutable_parameter_block_sizes()->push_back(3);
  for (int s = 0; s < chain_.size(); ++s) mutable_parameter_block_sizes()->push_back(4);
}

bool FloorResidual::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const int n = chain_.size();
  Eigen::Matrix3d rotation[kMaxChain];
  Eigen::Vector3d position[kMaxChain];
  if (!ChainForwardKinematics(*skeleton_, chain_, parameters, rotation, position)) return false;
  const Eigen::Vector3d& foot = position[n - 1];
  const double below = foot.y() - *lowest_height_;
  const bool active = below < 0.0;
  const double scale = active ? *scale_ : 0.0;
  residuals[0] = scale * below;
  if (jacobians == nullptr) return true;
  if (jacobians[0] != nullptr) {
    jacobians[0][0] = jacobians[0][2] = 0.0;
    jacobians[0][1] = scale;
  }
  for (int s = 0; s < n; ++s) {
    if (jacobians[1 + s] == nullptr) continue;
    // The y row of the plant's 3 x 3 tangent Jacobian, mapped to the ambient quaternion.
    const Eigen::Matrix<double, 1, 3> row = scale * (SkewSymmetric(position[s] - foot) * rotation[s]).row(1);
    double ambient[12];
    AmbientJacobianOfNormalized(Eigen::Matrix3d(row.replicate<3, 1>()), parameters[1 + s], ambient);
    for (int c = 0; c < 4; ++c) jacobians[1 + s][c] = ambient[c];
  }
  return true;
}

}  // namespace mocapsolve
