#include "problems/retarget/limb_direction_residual.h"

#include <glog/logging.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/retarget/foot_plant_residual.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

constexpr int kMaxChain = 128;

}  // namespace

Eigen::Vector3d LimbDirectionInJoint(const Skeleton& skeleton, const Pose& pose, int from, int to) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose, &fk);
  const Eigen::Vector3d world = fk.world_positions[to] - fk.world_positions[from];
  if (world.norm() <= 0.0) return Eigen::Vector3d::Zero();
  return fk.world_rotations[from].conjugate() * world.normalized();
}

LimbDirectionResidual::LimbDirectionResidual(const Skeleton* skeleton, int joint, const Eigen::Vector3d& local,
                                             const Eigen::Vector3d* goal, double scale)
    : skeleton_(skeleton), joint_(joint), local_(local), goal_(goal), scale_(scale),
      chain_(*skeleton, AncestorChain(*skeleton, joint)) {
  CHECK_LE(chain_.size(), kMaxChain) << "skeleton deeper than supported";
  set_num_residuals(3);
  mutable_parameter_block_sizes()->push_back(3);
  for (int s = 0; s < chain_.size(); ++s) mutable_parameter_block_sizes()->push_back(4);
}

bool LimbDirectionResidual::Evaluate(double const* const* parameters, double* residuals,
                                     double** jacobians) const {
  const int n = chain_.size();
  Eigen::Matrix3d rotation[kMaxChain];
  Eigen::Vector3d position[kMaxChain];
  if (!ChainForwardKinematics(*skeleton_, chain_, parameters, rotation, position)) return false;
  const Eigen::Vector3d direction = rotation[n - 1] * local_;
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = scale_ * (direction - *goal_);
  if (jacobians == nullptr) return true;
  if (jacobians[0] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(jacobians[0]).setZero();
  }
  for (int s = 0; s < n; ++s) {
    if (jacobians[1 + s] == nullptr) continue;
    AmbientJacobianOfNormalized(-scale_ * SkewSymmetric(direction) * rotation[s], parameters[1 + s],
                                jacobians[1 + s]);
  }
  return true;
}

}  // namespace mocapsolve
