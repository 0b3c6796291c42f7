#include "solvers/tree_dls_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include <Eigen/Geometry>
#include <glog/logging.h>

#include "kinematics/rotation.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

using Clock = std::chrono::steady_clock;

const Eigen::Matrix3d kIdentity = Eigen::Matrix3d::Identity();

double SecondsSince(Clock::time_point* t0) {
  const Clock::time_point t1 = Clock::now();
  const double seconds = std::chrono::duration<double>(t1 - *t0).count();
  *t0 = t1;
  return seconds;
}

// out = E_a(:, 0:A)^T x E_b(:, 0:B) in the top-left A x B corner, zeros elsewhere: a block
// of J^T J in the tangent coordinates of two joints of A and B dofs.
template <int A, int B>
void Transform(const Eigen::Matrix3d& ea, const Eigen::Matrix3d& x, const Eigen::Matrix3d& eb, Eigen::Matrix3d* out) {
  out->setZero();
  out->topLeftCorner<A, B>().noalias() = ea.leftCols<A>().transpose() * (x * eb.leftCols<B>());
}
using TransformKernel = void (*)(const Eigen::Matrix3d&, const Eigen::Matrix3d&, const Eigen::Matrix3d&,
                                 Eigen::Matrix3d*);
constexpr TransformKernel kTransforms[3][3] = {{Transform<1, 1>, Transform<1, 2>, Transform<1, 3>},
                                               {Transform<2, 1>, Transform<2, 2>, Transform<2, 3>},
                                               {Transform<3, 1>, Transform<3, 2>, Transform<3, 3>}};

}  // namespace

void TreeDlsSolver::Moments::SetZero() {
  s0 = k0 = k1 = 0.0;
  s1.setZero();
  k2.setZero();
  g0.setZero();
  g1.setZero();
  g2.setZero();
  s2.setZero();
}

void TreeDlsSolver::Moments::Add(const Moments& o) {
  s0 += o.s0;
  k0 += o.k0;
  k1 += o.k1;
  s1 += o.s1;
  k2 += o.k2;
  g0 += o.g0;
  g1 += o.g1;
  g2 += o.g2;
  s2 += o.s2;
}

TreeDlsSolver::TreeDlsSolver(const Skeleton* skeleton, double* translation, double* rotations)
    : skeleton_(skeleton), translation_(translation), rotations_(rotations),
      manifolds_(skeleton->num_joints(), nullptr) {}

void TreeDlsSolver::SetJointManifold(int joint, const ceres::Manifold* manifold) {
  CHECK(joint >= 0 && joint < skeleton_->num_joints());
  CHECK(manifold == nullptr || (manifold->AmbientSize() == 4 && manifold->TangentSize() <= 3));
  manifolds_[joint] = manifold;
  analyzed_ = false;
}

int TreeDlsSolver::AddRow(bool point, std::vector<TreeAttachment> attachments,
                          const Eigen::Vector3d* goal, double scale) {
  CHECK(!attachments.empty() && attachments.size() <= 32u) << "1 to 32 attachments per row";
  Row row;
  row.point = point;
  row.scale = scale;
  row.goal = goal;
  for (const TreeAttachment& a : attachments) {
    CHECK(a.joint >= 0 && a.joint < skeleton_->num_joints());
    row.total_weight += a.weight;
  }
  row.attachments = std::move(attachments);
  rows_.push_back(std::move(row));
  analyzed_ = false;
  return static_cast<int>(rows_.size()) - 1;
}

int TreeDlsSolver::AddPointRow(std::vector<TreeAttachment> attachments, const Eigen::Vector3d* goal,
                               double scale) {
  return AddRow(true, std::move(attachments), goal, scale);
}

int TreeDlsSolver::AddDirectionRow(std::vector<TreeAttachment> attachments,
                                   const Eigen::Vector3d* goal, double scale) {
  return AddRow(false, std::move(attachments), goal, scale);
}

void TreeDlsSolver::AddBlockCost(int joint, const ceres::CostFunction* cost) {
  CHECK(joint >= -1 && joint < skeleton_->num_joints());
  CHECK_EQ(cost->parameter_block_sizes().size(), 1u);
  CHECK_EQ(cost->parameter_block_sizes()[0], joint < 0 ? 3 : 4);
  block_costs_.push_back({joint, cost});
  analyzed_ = false;
}

void TreeDlsSolver::Analyze() {
  const int nj = skeleton_->num_joints();
  block_of_joint_.assign(nj, -1);
  joint_of_block_.assign(1, -1);
  tangent_size_.assign(1, 3);
  world_frame_.assign(1, 0);
  dof_manifolds_.assign(1, nullptr);
  for (int j = 0; j < nj; ++j) {
    if (manifolds_[j] == nullptr) continue;
    block_of_joint_[j] = static_cast<int>(joint_of_block_.size());
    joint_of_block_.push_back(j);
    tangent_size_.push_back(manifolds_[j]->TangentSize());
    world_frame_.push_back(dynamic_cast<const RightQuaternionManifold*>(manifolds_[j]) != nullptr);
    dof_manifolds_.push_back(dynamic_cast<const DofQuaternionManifold*>(manifolds_[j]));
  }
  const int nb = static_cast<int>(joint_of_block_.size());
  num_columns_ = 0;
  for (int b = 0; b < nb; ++b) num_columns_ += tangent_size_[b];
  solved_parent_.assign(nb, 0);
  for (int b = 1; b < nb; ++b) {
    for (int p = skeleton_->parent(joint_of_block_[b]); p >= 0; p = skeleton_->parent(p)) {
      if (block_of_joint_[p] > 0) {
        solved_parent_[b] = block_of_joint_[p];
        break;
      }
    }
  }
  for (const BlockCost& c : block_costs_) {
    CHECK(c.joint < 0 || block_of_joint_[c.joint] > 0) << "a block cost on a held joint " << c.joint;
  }

  pairs_.clear();
  std::map<std::pair<int, int>, int> ids;
  auto pair_id = [&](int a, int b) {
    if (a > b) std::swap(a, b);
    const auto it = ids.find({a, b});
    if (it != ids.end()) return it->second;
    const int id = static_cast<int>(pairs_.size());
    ids[{a, b}] = id;
    pairs_.push_back({a, b});
    return id;
  };
  for (int b = 0; b < nb; ++b) pair_id(b, b);
  ancestor_pairs_.assign(nb, {});
  for (int b = 1; b < nb; ++b) {
    ancestor_pairs_[b].push_back({0, pair_id(0, b)});
    std::vector<int> above;
    for (int a = b; a > 0; a = solved_parent_[a]) above.push_back(a);
    for (auto it = above.rbegin(); it != above.rend(); ++it) ancestor_pairs_[b].push_back({*it, pair_id(*it, b)});
  }

  std::vector<char> depends(nj, 0);
  for (Row& row : rows_) {
    std::vector<char> on_chain(nj, 0);
    for (const TreeAttachment& a : row.attachments) {
      for (int j = a.joint; j >= 0 && !on_chain[j]; j = skeleton_->parent(j)) on_chain[j] = 1;
    }
    row.chain.clear();
    for (int j = 0; j < nj; ++j) {
      depends[j] |= on_chain[j];
      if (on_chain[j] && block_of_joint_[j] > 0) row.chain.push_back(j);
    }
    const int na = static_cast<int>(row.attachments.size());
    const uint32_t all = na >= 32 ? ~0u : (1u << na) - 1;
    auto mask_of = [&](int j, double* cumulative) {
      uint32_t mask = 0;
      *cumulative = 0.0;
      for (int k = 0; k < na; ++k) {
        if (skeleton_->IsAncestorOrSelf(j, row.attachments[k].joint)) {
          mask |= 1u << k;
          *cumulative += row.attachments[k].weight;
        }
      }
      return mask;
    };
    const int nc = static_cast<int>(row.chain.size());
    row.full = 0;
    double cumulative = 0.0;
    while (row.full < nc && mask_of(row.chain[row.full], &cumulative) == all) ++row.full;
    row.moment_joint = row.full > 0 ? row.chain[row.full - 1] : -1;
    row.masks.clear();
    row.cumulative.clear();
    row.pair_ids.clear();
    for (int c = row.full; c < nc; ++c) {
      row.masks.push_back(mask_of(row.chain[c], &cumulative));
      row.cumulative.push_back(cumulative);
      const int a = block_of_joint_[row.chain[c]];
      row.pair_ids.push_back(pair_id(0, a));
      for (int i = 0; i <= c; ++i) row.pair_ids.push_back(pair_id(block_of_joint_[row.chain[i]], a));
    }
  }
  fk_joints_.clear();
  chain_joints_.clear();
  for (int j = 0; j < nj; ++j) {
    if (depends[j]) fk_joints_.push_back(j);
    if (depends[j] || block_of_joint_[j] > 0) chain_joints_.push_back(j);
  }
  // Leaves first: block b is block nb - 1 - b of the factor.
  std::vector<std::pair<int, int>> lower;
  pair_slot_.assign(pairs_.size(), -1);
  for (size_t id = 0; id < pairs_.size(); ++id) {
    const auto [a, b] = pairs_[id];
    if (a == b) continue;
    pair_slot_[id] = static_cast<int>(lower.size());
    lower.push_back({nb - 1 - a, nb - 1 - b});
  }
  std::vector<int> sizes(nb);
  for (int b = 0; b < nb; ++b) sizes[nb - 1 - b] = tangent_size_[b];
  cholesky_.Analyze(nb, lower, sizes);

  world_rotations_.resize(nj);
  world_positions_.resize(nj);
  bases_.assign(nb, Eigen::Matrix3d::Identity());
  plus_jacobians_.assign(nb, Eigen::Matrix<double, 4, 3>::Zero());
  moments_.resize(nb);
  accumulators_.resize(pairs_.size());
  gradient_world_.resize(nb);
  for (Linearization* l : {&current_, &saved_}) {
    l->blocks.resize(pairs_.size());
    l->gradient.resize(3 * nb);
    l->frames.resize(nb);
    l->extra_blocks.resize(nb);
    l->extra_gradient.resize(nb);
  }
  rhs_.resize(3 * nb);
  size_t max_chain = 0;
  for (const Row& row : rows_) max_chain = std::max(max_chain, row.chain.size());
  levers_.resize(max_chain + 1);
  points_.resize(32);
  analyzed_ = true;
}

void TreeDlsSolver::ForwardKinematics() {
  for (int j : fk_joints_) {
    Eigen::Quaterniond local = Eigen::Map<const Eigen::Quaterniond>(rotations_ + 4 * j);
    local.coeffs() /= local.norm();
    if (skeleton_->has_rest_rotation(j)) local = skeleton_->rest_rotation(j) * local;
    const int p = skeleton_->parent(j);
    if (p < 0) {
      world_positions_[j] = Eigen::Map<const Eigen::Vector3d>(translation_);
      world_rotations_[j] = local.toRotationMatrix();
    } else {
      world_positions_[j] = world_positions_[p] + world_rotations_[p] * skeleton_->offset(j);
      world_rotations_[j].noalias() = world_rotations_[p] * local.toRotationMatrix();
    }
  }
}

bool TreeDlsSolver::EvaluateRows(bool linearize, double* cost) {
  for (Row& row : rows_) {
    if (row.scale == 0.0) continue;
    const int na = static_cast<int>(row.attachments.size());
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < na; ++k) {
      const TreeAttachment& a = row.attachments[k];
      points_[k].noalias() = world_rotations_[a.joint] * a.local;
      if (row.point) points_[k] += world_positions_[a.joint];
      x += a.weight * points_[k];
    }
    const Eigen::Vector3d r = row.scale * (x - *row.goal);
    double factor = 1.0;
    const double squared = r.squaredNorm();
    if (loss_ != nullptr) {
      double rho[3];
      loss_->Evaluate(squared, rho);
      *cost += 0.5 * rho[0];
      factor = rho[1] > 0.0 ? std::sqrt(rho[1]) : 0.0;
    } else {
      *cost += 0.5 * squared;
    }
    if (!std::isfinite(squared)) return false;
    if (!linearize) continue;
    const double s = factor * row.scale;
    const Eigen::Vector3d re = factor * r;
    const double a = row.point ? s * row.total_weight : 0.0;
    const Eigen::Vector3d b = s * x;
    const double kappa = a * translation_scale_;
    Moments& m = moments_[row.moment_joint >= 0 ? block_of_joint_[row.moment_joint] : 0];
    m.s0 += a * a;
    m.s1 += a * b;
    m.s2.noalias() += b * b.transpose();
    m.k0 += kappa * kappa;
    m.k1 += kappa * a;
    m.k2 += kappa * b;
    m.g0 += kappa * re;
    m.g1 += a * re;
    m.g2 += re.cross(b);
    // Joints below the attachments' common ancestor: levers one by one.
    const int nc = static_cast<int>(row.chain.size());
    const int* ids = row.pair_ids.data();
    for (int c = row.full; c < nc; ++c) {
      const int j = row.chain[c];
      const int block = block_of_joint_[j];
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (uint32_t mask = row.masks[c - row.full]; mask != 0; mask &= mask - 1) {
        const int k = __builtin_ctz(mask);
        sum += row.attachments[k].weight * points_[k];
      }
      const Eigen::Vector3d u =
          row.point ? Eigen::Vector3d(s * (row.cumulative[c - row.full] * world_positions_[j] - sum))
                    : Eigen::Vector3d(-s * sum);
      levers_[c] = u;
      gradient_world_[block] += re.cross(u);
      accumulators_[*ids++] += kappa * SkewSymmetric(u);  // (translation, j).
      for (int i = 0; i <= c; ++i) {
        const Eigen::Vector3d ui = i < row.full ? Eigen::Vector3d(a * world_positions_[row.chain[i]] - b)
                                                : levers_[i];
        Eigen::Matrix3d& x_ij = accumulators_[*ids++];
        x_ij.diagonal().array() += ui.dot(u);
        x_ij.noalias() -= u * ui.transpose();
      }
    }
  }
  return true;
}

bool TreeDlsSolver::EvaluateBlockCosts(bool linearize, double* cost) {
  double residual[16];
  double ambient[64];
  for (const BlockCost& c : block_costs_) {
    const int nr = c.cost->num_residuals();
    CHECK_LE(nr, 16);
    double* parameters = c.joint < 0 ? translation_ : rotations_ + 4 * c.joint;
    const double* parameter_list[] = {parameters};
    double* jacobians[] = {ambient};
    if (!c.cost->Evaluate(parameter_list, residual, linearize ? jacobians : nullptr)) return false;
    const Eigen::Map<const Eigen::VectorXd> r(residual, nr);
    const double squared = r.squaredNorm();
    if (!std::isfinite(squared)) return false;
    *cost += 0.5 * squared;
    if (!linearize) continue;
    // J^T J and J^T r in the block's tangent coordinates (world-frame joints are rotated
    // once per block in Assemble).
    const int block = c.joint < 0 ? 0 : block_of_joint_[c.joint];
    Eigen::Matrix3d& jtj = current_.extra_blocks[block];
    Eigen::Vector3d& jtr = current_.extra_gradient[block];
    if (c.joint < 0) {
      const auto ambient_t = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(ambient, nr, 3);
      jtj.noalias() += (translation_scale_ * translation_scale_) * ambient_t.transpose() * ambient_t;
      jtr.noalias() += translation_scale_ * ambient_t.transpose() * r;
    } else if (nr == 4) {  // A rotation prior: fixed sizes.
      const Eigen::Matrix<double, 4, 3> tangent =
          Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(ambient) * plus_jacobians_[block];
      jtj.noalias() += tangent.transpose() * tangent;
      jtr.noalias() += tangent.transpose() * Eigen::Map<const Eigen::Vector4d>(residual);
    } else {
      const Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 16, 3> tangent =
          Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>>(ambient, nr, 4) *
          plus_jacobians_[block];
      jtj.noalias() += tangent.transpose() * tangent;
      jtr.noalias() += tangent.transpose() * r;
    }
  }
  return true;
}

void TreeDlsSolver::Assemble() {
  const int nb = static_cast<int>(joint_of_block_.size());
  // Moments summed up the tree (children before parents: reverse preorder); each block's
  // subtree sum is expanded into its ancestor pairs on the way.
  for (int k = nb - 1; k >= 1; --k) {
    const Moments& m = moments_[k];
    const Eigen::Vector3d& ok = world_positions_[joint_of_block_[k]];
    const double trace = m.s2.trace();
    const Eigen::Vector3d w = m.s0 * ok - m.s1;
    const double ok_s1 = ok.dot(m.s1);
    for (const auto& [j, id] : ancestor_pairs_[k]) {
      Eigen::Matrix3d& x = accumulators_[id];
      if (j == 0) {
        x += SkewSymmetric(m.k1 * ok - m.k2);
        continue;
      }
      const Eigen::Vector3d& oj = world_positions_[joint_of_block_[j]];
      const Eigen::Vector3d v = m.s0 * oj - m.s1;
      x.noalias() += m.s1 * oj.transpose();
      x.noalias() -= ok * v.transpose();
      x -= m.s2;
      x.diagonal().array() += oj.dot(w) - ok_s1 + trace;
    }
    gradient_world_[k] += m.g1.cross(ok) - m.g2;
    moments_[solved_parent_[k]].Add(m);
  }
  gradient_world_[0] += moments_[0].g0;
  accumulators_[0].diagonal().array() += moments_[0].k0;  // Pair (0, 0) has id 0.

  // Blocks in solve coordinates: E_a^T X E_b (E = I for the translation and world-frame
  // joints).
  for (size_t id = 0; id < pairs_.size(); ++id) {
    const auto [a, b] = pairs_[id];
    Eigen::Matrix3d& block = current_.blocks[id];
    const bool left = a > 0 && !world_frame_[a], right = b > 0 && !world_frame_[b];
    if (!left && !right) {
      block = accumulators_[id];
    } else {
      kTransforms[tangent_size_[a] - 1][tangent_size_[b] - 1](left ? bases_[a] : kIdentity, accumulators_[id],
                                                               right ? bases_[b] : kIdentity, &block);
    }
    if (a == b) {
      if (a > 0 && world_frame_[a]) {  // delta = R^T omega.
        const Eigen::Matrix3d& r = world_rotations_[joint_of_block_[a]];
        block.noalias() += r * current_.extra_blocks[a] * r.transpose();
      } else {
        block += current_.extra_blocks[a];
      }
    }
  }
  double max_gradient = 0.0;
  for (int b = 0; b < nb; ++b) {
    Eigen::Vector3d g = gradient_world_[b];
    if (b > 0 && !world_frame_[b]) {
      g = bases_[b].transpose() * g + current_.extra_gradient[b];
    } else if (b > 0) {
      g.noalias() += world_rotations_[joint_of_block_[b]] * current_.extra_gradient[b];
    } else {
      g += current_.extra_gradient[b];
    }
    current_.gradient.segment<3>(3 * b) = g;
    current_.frames[b] = b > 0 ? world_rotations_[joint_of_block_[b]] : Eigen::Matrix3d::Identity();
    // The stopping rule reads the gradient in the tangent coordinates (delta, not omega).
    const Eigen::Vector3d tangent = b > 0 && world_frame_[b] ? Eigen::Vector3d(current_.frames[b].transpose() * g) : g;
    for (int i = 0; i < tangent_size_[b]; ++i) max_gradient = std::max(max_gradient, std::abs(tangent[i]));
  }
  current_.max_gradient = max_gradient;
}

bool TreeDlsSolver::Evaluate(bool linearize, double* cost) {
  Clock::time_point t0;
  if (time_stages_) t0 = Clock::now();
  ForwardKinematics();
  if (time_stages_) times_.fk += SecondsSince(&t0);
  const int nb = static_cast<int>(joint_of_block_.size());
  if (linearize) {
    for (Moments& m : moments_) m.SetZero();
    for (Eigen::Matrix3d& x : accumulators_) x.setZero();
    for (Eigen::Vector3d& g : gradient_world_) g.setZero();
    for (int b = 0; b < nb; ++b) {
      current_.extra_blocks[b].setZero();
      current_.extra_gradient[b].setZero();
    }
    for (int b = 1; b < nb; ++b) {
      const int j = joint_of_block_[b];
      const double* q = rotations_ + 4 * j;
      if (world_frame_[b]) {
        plus_jacobians_[b] = QuaternionPlusJacobian(q);
        continue;
      }
      const int k = tangent_size_[b];
      double plus[12];
      const DofQuaternionManifold* dof = dof_manifolds_[b];
      if (dof == nullptr || !dof->PlusJacobianOnSet(q, plus)) manifolds_[j]->PlusJacobian(q, plus);
      plus_jacobians_[b].setZero();
      for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < k; ++c) plus_jacobians_[b](r, c) = plus[r * k + c];
      }
      Eigen::Vector4d unit = Eigen::Map<const Eigen::Vector4d>(q);
      const double norm = unit.norm();
      unit /= norm;
      // E = R B, B = AmbientFromTangent(q) P / |q| (the local increment of each tangent
      // coordinate, as the residuals' ambient Jacobians imply), padded with zeros.
      bases_[b].noalias() = world_rotations_[j] * (AmbientFromTangent(unit.data()) * plus_jacobians_[b] / norm);
    }
  }
  *cost = 0.0;
  if (!EvaluateRows(linearize, cost) || !EvaluateBlockCosts(linearize, cost)) return false;
  if (!std::isfinite(*cost)) return false;
  if (time_stages_) times_.rows += SecondsSince(&t0);
  if (linearize) {
    Assemble();
    if (time_stages_) times_.assembly += SecondsSince(&t0);
  }
  return true;
}

double TreeDlsSolver::MaxGradient() const { return current_.max_gradient; }

bool TreeDlsSolver::ComputeStep(double lambda, Eigen::VectorXd* delta) {
  Clock::time_point t0;
  if (time_stages_) t0 = Clock::now();
  const int nb = static_cast<int>(joint_of_block_.size());
  cholesky_.SetZero();
  for (size_t id = 0; id < pairs_.size(); ++id) {
    const auto [a, b] = pairs_[id];
    if (a != b) {
      cholesky_.Block(pair_slot_[id]) = current_.blocks[id];
      continue;
    }
    Eigen::Matrix3d& d = cholesky_.Diagonal(nb - 1 - a);
    d = current_.blocks[id];
    for (int i = 0; i < 3; ++i) {
      if (i < tangent_size_[a]) {
        d(i, i) += lambda;
      } else {
        d(i, i) = 1.0;  // Padding of an ASF joint: decoupled, its step is 0.
      }
    }
  }
  bool ok = cholesky_.Factorize();
  if (ok) {
    for (int b = 0; b < nb; ++b) rhs_.segment<3>(3 * (nb - 1 - b)) = -current_.gradient.segment<3>(3 * b);
    cholesky_.Solve(rhs_, &step_);
    delta->resize(num_columns_);
    int offset = 0;
    for (int b = 0; b < nb; ++b) {
      Eigen::Vector3d s = step_.segment<3>(3 * (nb - 1 - b));
      if (b > 0 && world_frame_[b]) s = current_.frames[b].transpose() * s;  // omega -> delta.
      delta->segment(offset, tangent_size_[b]) = s.head(tangent_size_[b]);
      offset += tangent_size_[b];
    }
  }
  if (time_stages_) {
    times_.solve += SecondsSince(&t0);
    ++times_.steps;
  }
  return ok;
}

void TreeDlsSolver::Save() {
  std::swap(current_, saved_);
  std::vector<double>& p = saved_.saved_parameters;
  p.assign(translation_, translation_ + 3);
  for (int j : chain_joints_) {
    if (block_of_joint_[j] > 0) p.insert(p.end(), rotations_ + 4 * j, rotations_ + 4 * j + 4);
  }
}

void TreeDlsSolver::Restore() {
  std::swap(current_, saved_);
  const std::vector<double>& p = current_.saved_parameters;
  std::copy(p.begin(), p.begin() + 3, translation_);
  size_t i = 3;
  for (int j : chain_joints_) {
    if (block_of_joint_[j] <= 0) continue;
    std::copy(p.begin() + i, p.begin() + i + 4, rotations_ + 4 * j);
    i += 4;
  }
}

bool TreeDlsSolver::ApplyStep(const Eigen::VectorXd& delta, double* step_norm, double* x_norm) {
  Clock::time_point t0;
  if (time_stages_) t0 = Clock::now();
  *step_norm = delta.norm();
  double x_sq = 0.0;
  for (int i = 0; i < 3; ++i) x_sq += translation_[i] * translation_[i];
  for (int j : chain_joints_) x_sq += Eigen::Map<const Eigen::Vector4d>(rotations_ + 4 * j).squaredNorm();
  *x_norm = std::sqrt(x_sq);
  for (int i = 0; i < 3; ++i) translation_[i] += translation_scale_ * delta[i];
  const int nb = static_cast<int>(joint_of_block_.size());
  int offset = 3;
  bool ok = true;
  for (int b = 1; b < nb && ok; ++b) {
    double* q = rotations_ + 4 * joint_of_block_[b];
    double out[4];
    ok = manifolds_[joint_of_block_[b]]->Plus(q, delta.data() + offset, out);
    std::copy(out, out + 4, q);
    offset += tangent_size_[b];
  }
  if (time_stages_) times_.update += SecondsSince(&t0);
  return ok;
}

void TreeDlsSolver::Solve(const DlsOptions& options, DlsSummary* summary) {
  if (!analyzed_) Analyze();
  RunDlsIterations(options, this, summary);
}

int TreeDlsSolver::num_factor_blocks() {
  if (!analyzed_) Analyze();
  return cholesky_.num_factor_blocks();
}

void TreeDlsSolver::Linearize(Eigen::VectorXd* residual, Eigen::MatrixXd* jacobian) {
  if (!analyzed_) Analyze();
  ForwardKinematics();
  const int nr = static_cast<int>(rows_.size());
  residual->setZero(3 * nr);
  jacobian->setZero(3 * nr, 3 + 3 * skeleton_->num_joints());
  for (int i = 0; i < nr; ++i) {
    const Row& row = rows_[i];
    const int na = static_cast<int>(row.attachments.size());
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < na; ++k) {
      const TreeAttachment& a = row.attachments[k];
      points_[k] = world_rotations_[a.joint] * a.local;
      if (row.point) points_[k] += world_positions_[a.joint];
      x += a.weight * points_[k];
    }
    residual->segment<3>(3 * i) = row.scale * (x - *row.goal);
    if (row.point) jacobian->block<3, 3>(3 * i, 0) = row.scale * row.total_weight * Eigen::Matrix3d::Identity();
    for (int j : row.chain) {
      Eigen::Vector3d u = Eigen::Vector3d::Zero();
      for (int k = 0; k < na; ++k) {
        const TreeAttachment& a = row.attachments[k];
        if (!skeleton_->IsAncestorOrSelf(j, a.joint)) continue;
        u += a.weight * (row.point ? Eigen::Vector3d(world_positions_[j] - points_[k]) : Eigen::Vector3d(-points_[k]));
      }
      jacobian->block<3, 3>(3 * i, 3 + 3 * j) = row.scale * SkewSymmetric(u) * world_rotations_[j];
    }
  }
}

}  // namespace mocapsolve
