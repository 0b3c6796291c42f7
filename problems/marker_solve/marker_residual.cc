#include "problems/marker_solve/marker_residual.h"

#include <algorithm>

#include <Eigen/Geometry>
#include <glog/logging.h>

#include "kinematics/rotation.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

// Chains are short (<= the skeleton depth); this keeps Evaluate free of allocation.
constexpr int kMaxChain = 64;

}  // namespace

MarkerResidual::MarkerResidual(const Skeleton* skeleton, const MarkerSet* marker_set, int marker,
                               const Eigen::Vector3d* observed, double weight)
    : skeleton_(skeleton), marker_set_(marker_set), marker_(marker), observed_(observed),
      weight_(weight), chain_(*skeleton, marker_set->InfluencingJoints(marker)) {
  CHECK_LE(chain_.size(), kMaxChain) << "skeleton deeper than supported";
  CHECK(chain_.size() > 0 && chain_.joints[0] == 0);
  set_num_residuals(3);
  mutable_parameter_block_sizes()->push_back(3);
  for (int s = 0; s < chain_.size(); ++s) mutable_parameter_block_sizes()->push_back(4);
  for (const MarkerAttachment& a : marker_set->marker(marker).attachments) attachment_slot_.push_back(chain_.slot(a.joint));
}

bool MarkerResidual::Evaluate(double const* const* parameters, double* residuals,
                              double** jacobians) const {
  Eigen::Matrix3d rotation[kMaxChain];
  Eigen::Vector3d position[kMaxChain];
  if (!ChainForwardKinematics(*skeleton_, chain_, parameters, rotation, position)) return false;
  const auto& attachments = marker_set_->marker(marker_).attachments;
  Eigen::Vector3d points[kMaxChain];  // p_mk, one per attachment (few).
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < attachments.size(); ++k) {
    const int s = attachment_slot_[k];
    points[k] = position[s] + rotation[s] * attachments[k].offset;
    x += attachments[k].weight * points[k];
  }
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = weight_ * (x - *observed_);
  if (jacobians == nullptr) return true;

  if (jacobians[0] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> jt(jacobians[0]);
    jt = weight_ * Eigen::Matrix3d::Identity();
  }
  for (int s = 0; s < chain_.size(); ++s) {
    if (jacobians[1 + s] == nullptr) continue;
    const int j = chain_.joints[s];
    // sum over attachments in subtree(j) of w [o_j - p]x, then times R_j.
    Eigen::Matrix3d lever = Eigen::Matrix3d::Zero();
    for (size_t k = 0; k < attachments.size(); ++k) {
      if (skeleton_->IsAncestorOrSelf(j, attachments[k].joint)) {
        lever += attachments[k].weight * SkewSymmetric(position[s] - points[k]);
      }
    }
    AmbientJacobianOfNormalized(weight_ * lever * rotation[s], parameters[1 + s], jacobians[1 + s]);
  }
  return true;
}

}  // namespace mocapsolve
