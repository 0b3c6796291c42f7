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
      weight_(weight), chain_(marker_set->InfluencingJoints(marker)) {
  CHECK_LE(static_cast<int>(chain_.size()), kMaxChain) << "skeleton deeper than supported";
  CHECK(!chain_.empty() && chain_[0] == 0);
  set_num_residuals(3);
  mutable_parameter_block_sizes()->push_back(3);
  for (size_t s = 0; s < chain_.size(); ++s) mutable_parameter_block_sizes()->push_back(4);
  for (size_t s = 0; s < chain_.size(); ++s) {
    const int parent = skeleton->parent(chain_[s]);
    parent_slot_.push_back(parent < 0 ? -1
                                      : static_cast<int>(std::lower_bound(chain_.begin(), chain_.end(), parent) - chain_.begin()));
  }
  for (const MarkerAttachment& a : marker_set->marker(marker).attachments) {
    attachment_slot_.push_back(
        static_cast<int>(std::lower_bound(chain_.begin(), chain_.end(), a.joint) - chain_.begin()));
  }
}

bool MarkerResidual::Evaluate(double const* const* parameters, double* residuals,
                              double** jacobians) const {
  const int n = static_cast<int>(chain_.size());
  Eigen::Quaterniond rotation[kMaxChain];
  Eigen::Vector3d position[kMaxChain];
  for (int s = 0; s < n; ++s) {
    const int j = chain_[s];
    Eigen::Quaterniond local = Eigen::Map<const Eigen::Quaterniond>(parameters[1 + s]);
    const double norm = local.norm();
    if (!(norm > 0.0)) return false;
    local.coeffs() /= norm;
    if (skeleton_->has_rest_rotation(j)) local = skeleton_->rest_rotation(j) * local;
    if (parent_slot_[s] < 0) {
      position[s] = Eigen::Map<const Eigen::Vector3d>(parameters[0]);
      rotation[s] = local;
    } else {
      const int p = parent_slot_[s];
      position[s] = position[p] + rotation[p] * skeleton_->offset(j);
      rotation[s] = rotation[p] * local;
    }
  }
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
  for (int s = 0; s < n; ++s) {
    if (jacobians[1 + s] == nullptr) continue;
    const int j = chain_[s];
    // sum over attachments in subtree(j) of w [o_j - p]x, then times R_j.
    Eigen::Matrix3d lever = Eigen::Matrix3d::Zero();
    for (size_t k = 0; k < attachments.size(); ++k) {
      if (skeleton_->IsAncestorOrSelf(j, attachments[k].joint)) {
        lever += attachments[k].weight * SkewSymmetric(position[s] - points[k]);
      }
    }
    const Eigen::Matrix3d tangent = weight_ * lever * rotation[s].toRotationMatrix();
    Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> jq(jacobians[1 + s]);
    // r depends on q / |q|: the ambient derivative carries the 1 / |q| of that map.
    Eigen::Vector4d q = Eigen::Map<const Eigen::Vector4d>(parameters[1 + s]);
    const double norm = q.norm();
    q /= norm;
    jq = tangent * AmbientFromTangent(q.data()) / norm;
  }
  return true;
}

}  // namespace mocapsolve
