#include "problems/retarget/tracked_vertex_residual.h"

#include <algorithm>

#include <glog/logging.h>

#include "kinematics/rotation.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

constexpr int kMaxChain = 128;
constexpr int kMaxInfluences = 32;

}  // namespace

std::vector<int> VertexChain(const Skeleton& skeleton, const SkinnedMesh& mesh, int vertex) {
  std::vector<bool> in_chain(skeleton.num_joints(), false);
  for (int k = mesh.weight_begin(vertex); k < mesh.weight_end(vertex); ++k) {
    for (int j = mesh.weight_joint(k); j >= 0 && !in_chain[j]; j = skeleton.parent(j)) {
      in_chain[j] = true;
    }
  }
  in_chain[0] = true;
  std::vector<int> chain;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    if (in_chain[j]) chain.push_back(j);
  }
  return chain;
}

TrackedVertexResidual::TrackedVertexResidual(const Skeleton* skeleton, const SkinnedMesh* mesh,
                                             int vertex, bool track_position,
                                             const Eigen::Vector3d* goal, double scale)
    : skeleton_(skeleton), vertex_(vertex), track_position_(track_position), goal_(goal),
      scale_(scale), chain_(*skeleton, VertexChain(*skeleton, *mesh, vertex)) {
  CHECK_LE(chain_.size(), kMaxChain) << "skeleton deeper than supported";
  CHECK_LE(mesh->weight_end(vertex) - mesh->weight_begin(vertex), kMaxInfluences);
  CHECK(track_position || mesh->has_normals());
  set_num_residuals(3);
  mutable_parameter_block_sizes()->push_back(3);
  for (int s = 0; s < chain_.size(); ++s) mutable_parameter_block_sizes()->push_back(4);
  auto slot_of = [this](int joint) { return chain_.slot(joint); };
  for (int k = mesh->weight_begin(vertex); k < mesh->weight_end(vertex); ++k) {
    const int b = mesh->weight_joint(k);
    const Eigen::Isometry3d& joint_from_bind = mesh->joint_from_bind(b);
    Influence influence;
    influence.slot = slot_of(b);
    influence.weight = mesh->weight(k);
    influence.local = track_position
                          ? Eigen::Vector3d(joint_from_bind * mesh->rest_positions().col(vertex))
                          : Eigen::Vector3d(joint_from_bind.linear() * mesh->rest_normals().col(vertex));
    influences_.push_back(influence);
  }
}

bool TrackedVertexResidual::Evaluate(double const* const* parameters, double* residuals,
                                     double** jacobians) const {
  const int n = chain_.size();
  Eigen::Matrix3d rotation[kMaxChain];
  Eigen::Vector3d position[kMaxChain];
  if (!ChainForwardKinematics(*skeleton_, chain_, parameters, rotation, position)) return false;
  // p_b (position) or R_b y_b (normal), one per influence.
  Eigen::Vector3d terms[kMaxInfluences];
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  const int ni = static_cast<int>(influences_.size());
  for (int k = 0; k < ni; ++k) {
    const Influence& influence = influences_[k];
    terms[k] = rotation[influence.slot] * influence.local;
    if (track_position_) terms[k] += position[influence.slot];
    x += influence.weight * terms[k];
  }
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = scale_ * (x - *goal_);
  if (jacobians == nullptr) return true;

  if (jacobians[0] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> jt(jacobians[0]);
    if (track_position_) {
      double total = 0.0;
      for (const Influence& influence : influences_) total += influence.weight;
      jt = scale_ * total * Eigen::Matrix3d::Identity();
    } else {
      jt.setZero();
    }
  }
  for (int s = 0; s < n; ++s) {
    if (jacobians[1 + s] == nullptr) continue;
    const int j = chain_.joints[s];
    Eigen::Vector3d lever = Eigen::Vector3d::Zero();  // sum w_b (o_j - p_b) or -sum w_b n_b.
    for (int k = 0; k < ni; ++k) {
      if (skeleton_->IsAncestorOrSelf(j, chain_.joints[influences_[k].slot])) {
        lever += influences_[k].weight *
                 (track_position_ ? Eigen::Vector3d(position[s] - terms[k]) : Eigen::Vector3d(-terms[k]));
      }
    }
    AmbientJacobianOfNormalized(scale_ * SkewSymmetric(lever) * rotation[s], parameters[1 + s], jacobians[1 + s]);
  }
  return true;
}

}  // namespace mocapsolve
