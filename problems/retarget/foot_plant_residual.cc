#include "problems/retarget/foot_plant_residual.h"

#include <glog/logging.h>

#include "kinematics/rotation.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

constexpr int kMaxChain = 128;

}  // namespace

std::vector<int> AncestorChain(const Skeleton& skeleton, int joint) {
  std::vector<int> chain;
  for (int j = joint; j >= 0; j = skeleton.parent(j)) chain.insert(chain.begin(), j);
  return chain;
}

FootPlantResidual::FootPlantResidual(const Skeleton* skeleton, int joint, const Eigen::Vector3d* anchor,
                                     const double* scale)
    : skeleton_(skeleton), joint_(joint), anchor_(anchor), scale_(scale),
      chain_(*skeleton, AncestorChain(*skeleton, joint)) {
  CHECK_LE(chain_.size(), kMaxChain) << "skeleton deeper than supported";
  set_num_residuals(3);
  mutable_parameter_block_sizes()->push_back(3);
  for (int s = 0; s < chain_.size(); ++s) mutable_parameter_block_sizes()->push_back(4);
}

bool FootPlantResidual::Evaluate(double const* const* parameters, double* residuals,
                                 double** jacobians) const {
  const int n = chain_.size();
  Eigen::Matrix3d rotation[kMaxChain];
  Eigen::Vector3d position[kMaxChain];
  if (!ChainForwardKinematics(*skeleton_, chain_, parameters, rotation, position)) return false;
  const double scale = *scale_;
  const Eigen::Vector3d& foot = position[n - 1];
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = scale * (foot - *anchor_);
  if (jacobians == nullptr) return true;
  if (jacobians[0] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> jt(jacobians[0]);
    jt = scale * Eigen::Matrix3d::Identity();
  }
  for (int s = 0; s < n; ++s) {
    if (jacobians[1 + s] == nullptr) continue;
    AmbientJacobianOfNormalized(scale * SkewSymmetric(position[s] - foot) * rotation[s], parameters[1 + s],
                                jacobians[1 + s]);
  }
  return true;
}

}  // namespace mocapsolve
