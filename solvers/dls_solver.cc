#include "solvers/dls_solver.h"

#include <cmath>
#include <cstdio>

#include <algorithm>
#include <chrono>
#include <unordered_map>

#include <Eigen/Cholesky>
#include <glog/logging.h>

namespace mocapsolve {
namespace {

// Fixed-size kernels for the common 3-row residual blocks with 1-3 tangent columns per
// parameter block (joint dofs): dynamic-size Eigen products of 3 x 3 blocks cost more in
// bookkeeping than in arithmetic.
template <int A, int B>
void AddTransposeProduct(const double* ja, const double* jb, int row, int col, Eigen::MatrixXd* jtj) {
  jtj->block<A, B>(row, col).noalias() +=
      Eigen::Map<const Eigen::Matrix<double, 3, A>>(ja).transpose() *
      Eigen::Map<const Eigen::Matrix<double, 3, B>>(jb);
}

using ProductKernel = void (*)(const double*, const double*, int, int, Eigen::MatrixXd*);

// The same product into a pair block of the sparse forms (A x B, column-major).
template <int A, int B>
void AddTransposeProductTo(const double* ja, const double* jb, double* block) {
  Eigen::Map<Eigen::Matrix<double, A, B>>(block).noalias() +=
      Eigen::Map<const Eigen::Matrix<double, 3, A>>(ja).transpose() *
      Eigen::Map<const Eigen::Matrix<double, 3, B>>(jb);
}
using PairKernel = void (*)(const double*, const double*, double*);
constexpr PairKernel kPairKernels[3][3] = {
    {AddTransposeProductTo<1, 1>, AddTransposeProductTo<1, 2>, AddTransposeProductTo<1, 3>},
    {AddTransposeProductTo<2, 1>, AddTransposeProductTo<2, 2>, AddTransposeProductTo<2, 3>},
    {AddTransposeProductTo<3, 1>, AddTransposeProductTo<3, 2>, AddTransposeProductTo<3, 3>}};
constexpr ProductKernel kProductKernels[3][3] = {
    {AddTransposeProduct<1, 1>, AddTransposeProduct<1, 2>, AddTransposeProduct<1, 3>},
    {AddTransposeProduct<2, 1>, AddTransposeProduct<2, 2>, AddTransposeProduct<2, 3>},
    {AddTransposeProduct<3, 1>, AddTransposeProduct<3, 2>, AddTransposeProduct<3, 3>}};

template <int T>
void QuaternionTangent(const double* ambient, const double* plus, double scale, double* tangent) {
  Eigen::Map<Eigen::Matrix<double, 3, T>>(tangent).noalias() =
      scale * Eigen::Map<const Eigen::Matrix<double, 3, 4, Eigen::RowMajor>>(ambient) *
      Eigen::Map<const Eigen::Matrix<double, 4, T, (T == 1 ? Eigen::ColMajor : Eigen::RowMajor)>>(plus);
}
using TangentKernel = void (*)(const double*, const double*, double, double*);
constexpr TangentKernel kTangentKernels[3] = {QuaternionTangent<1>, QuaternionTangent<2>,
                                              QuaternionTangent<3>};

}  // namespace

bool ParseDlsLinearSolver(const std::string& name, DlsLinearSolver* solver) {
  if (name == "dense") return *solver = DlsLinearSolver::kDense, true;
  if (name == "sparse_ldlt") return *solver = DlsLinearSolver::kSparseLdlt, true;
  if (name == "block_banded") return *solver = DlsLinearSolver::kBlockBanded, true;
  return false;
}

DlsSolver::DlsSolver(DlsLinearSolver linear_solver, int band_block_columns)
    : linear_solver_(linear_solver), band_block_columns_(band_block_columns) {
  CHECK(linear_solver != DlsLinearSolver::kBlockBanded || band_block_columns > 0)
      << "kBlockBanded needs the columns per band block";
}

int DlsProblem::AddParameterBlock(double* values, int size, const ceres::Manifold* manifold) {
  Parameter p;
  p.values = values;
  p.size = size;
  p.manifold = manifold;
  p.tangent_size = manifold != nullptr ? manifold->TangentSize() : size;
  parameters_.push_back(p);
  return static_cast<int>(parameters_.size()) - 1;
}

void DlsProblem::SetParameterBlockConstant(int block) { parameters_[block].constant = true; }

void DlsProblem::AddResidualBlock(const ceres::CostFunction* cost, const ceres::LossFunction* loss,
                                  std::vector<int> blocks) {
  residuals_.push_back({cost, loss, std::move(blocks)});
}

void DlsProblem::Clear() {
  parameters_.clear();
  residuals_.clear();
}

bool DlsSolver::Evaluate(bool linearize, double* cost) {
  DlsProblem* problem = problem_;
  const bool dense_j = dense_j_;
  if (linearize) {
    jtr_.setZero(num_cols_);
    if (dense_j) {
      jacobian_.setZero(num_rows_, num_cols_);
      residual_.resize(num_rows_);
    } else if (linear_solver_ == DlsLinearSolver::kDense) {
      jtj_.setZero(num_cols_, num_cols_);
    } else {
      pair_values_.assign(pair_values_.size(), 0.0);
    }
  }
  if (linearize) {
    // Each block's PlusJacobian once, not once per residual that touches it.
    plus_offset_.resize(problem->parameters_.size());
    size_t total = 0;
    for (size_t b = 0; b < problem->parameters_.size(); ++b) {
      const DlsProblem::Parameter& p = problem->parameters_[b];
      plus_offset_[b] = total;
      if (p.manifold != nullptr && !p.constant) total += p.size * p.tangent_size;
    }
    plus_jacobians_.resize(total);
    for (size_t b = 0; b < problem->parameters_.size(); ++b) {
      const DlsProblem::Parameter& p = problem->parameters_[b];
      if (p.manifold != nullptr && !p.constant) {
        p.manifold->PlusJacobian(p.values, &plus_jacobians_[plus_offset_[b]]);
      }
    }
  }
  *cost = 0.0;
  int row = 0;
  std::vector<const double*> parameter_pointers;
  std::vector<double*> jacobian_pointers;
  const bool sparse = linear_solver_ != DlsLinearSolver::kDense;
  for (size_t i = 0; i < problem->residuals_.size(); ++i) {
    const DlsProblem::Residual& block = problem->residuals_[i];
    const int nr = block.cost->num_residuals();
    const int nb = static_cast<int>(block.blocks.size());
    r_.resize(nr);
    parameter_pointers.resize(nb);
    jacobian_pointers.resize(nb);
    if (static_cast<int>(ambient_.size()) < nb) {
      ambient_.resize(nb);
      tangent_.resize(nb);
    }
    for (int k = 0; k < nb; ++k) {
      const DlsProblem::Parameter& p = problem->parameters_[block.blocks[k]];
      parameter_pointers[k] = p.values;
      ambient_[k].resize(nr * p.size);
      jacobian_pointers[k] = linearize && !p.constant ? ambient_[k].data() : nullptr;
    }
    if (!block.cost->Evaluate(parameter_pointers.data(), r_.data(),
                              linearize ? jacobian_pointers.data() : nullptr)) {
      return false;
    }
    Eigen::Map<Eigen::VectorXd> r(r_.data(), nr);
    if (!r.allFinite()) return false;
    double scale = 1.0;
    if (block.loss != nullptr) {
      double rho[3];
      block.loss->Evaluate(r.squaredNorm(), rho);
      *cost += 0.5 * rho[0];
      scale = rho[1] > 0.0 ? std::sqrt(rho[1]) : 0.0;
    } else {
      *cost += 0.5 * r.squaredNorm();
    }
    if (!linearize) continue;
    r *= scale;
    // Tangent Jacobians of this block, scaled like the residual.
    for (int k = 0; k < nb; ++k) {
      const DlsProblem::Parameter& p = problem->parameters_[block.blocks[k]];
      if (p.constant) continue;
      const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
          ambient(ambient_[k].data(), nr, p.size);
      tangent_[k].resize(nr, p.tangent_size);
      if (p.manifold == nullptr) {
        tangent_[k] = scale * ambient;
      } else {
        const double* plus_jacobian = &plus_jacobians_[plus_offset_[block.blocks[k]]];
        if (nr == 3 && p.size == 4 && p.tangent_size <= 3) {
          kTangentKernels[p.tangent_size - 1](ambient_[k].data(), plus_jacobian, scale,
                                             tangent_[k].data());
        } else {
          const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
              plus(plus_jacobian, p.size, p.tangent_size);
          tangent_[k].noalias() = scale * ambient * plus;
        }
      }
      if (nr == 3 && p.tangent_size == 3) {
        jtr_.segment<3>(p.tangent_offset).noalias() +=
            Eigen::Map<const Eigen::Matrix3d>(tangent_[k].data()).transpose() *
            Eigen::Map<const Eigen::Vector3d>(r_.data());
      } else {
        jtr_.segment(p.tangent_offset, p.tangent_size).noalias() += tangent_[k].transpose() * r;
      }
    }
    if (dense_j) {
      residual_.segment(row, nr) = r;
      for (int k = 0; k < nb; ++k) {
        const DlsProblem::Parameter& p = problem->parameters_[block.blocks[k]];
        if (p.constant) continue;
        jacobian_.block(row, p.tangent_offset, nr, p.tangent_size) += tangent_[k];
      }
    } else if (sparse) {
      // Into the residual's pair blocks, in the order Setup listed them.
      const int* slot = pair_slot_.data() + residual_pairs_[i];
      for (int a = 0; a < nb; ++a) {
        const DlsProblem::Parameter& pa = problem->parameters_[block.blocks[a]];
        if (pa.constant) continue;
        for (int b = 0; b < nb; ++b) {
          const DlsProblem::Parameter& pb = problem->parameters_[block.blocks[b]];
          if (pb.constant || pb.tangent_offset < pa.tangent_offset) continue;
          double* target = &pair_values_[pairs_[*slot++].offset];
          if (nr == 3 && pa.tangent_size <= 3 && pb.tangent_size <= 3) {
            kPairKernels[pa.tangent_size - 1][pb.tangent_size - 1](tangent_[a].data(), tangent_[b].data(), target);
          } else {
            Eigen::Map<Eigen::MatrixXd>(target, pa.tangent_size, pb.tangent_size).noalias() +=
                tangent_[a].transpose() * tangent_[b];
          }
        }
      }
    } else {
      // J^T J, block-sparse: only pairs of blocks this residual touches, upper triangle
      // (mirrored in Solve), with a fixed-size path for the common 3-row, 3-column case.
      for (int a = 0; a < nb; ++a) {
        const DlsProblem::Parameter& pa = problem->parameters_[block.blocks[a]];
        if (pa.constant) continue;
        for (int b = 0; b < nb; ++b) {
          const DlsProblem::Parameter& pb = problem->parameters_[block.blocks[b]];
          if (pb.constant || pb.tangent_offset < pa.tangent_offset) continue;
          if (nr == 3 && pa.tangent_size <= 3 && pb.tangent_size <= 3) {
            kProductKernels[pa.tangent_size - 1][pb.tangent_size - 1](
                tangent_[a].data(), tangent_[b].data(), pa.tangent_offset, pb.tangent_offset, &jtj_);
          } else {
            jtj_.block(pa.tangent_offset, pb.tangent_offset, pa.tangent_size, pb.tangent_size)
                .noalias() += tangent_[a].transpose() * tangent_[b];
          }
        }
      }
    }
    row += nr;
  }
  return true;
}

// Swaps, not copies: the next Evaluate rebuilds jtr_/jtj_ from zero anyway.
void DlsSolver::Save() {
  saved_.clear();
  for (const auto& p : problem_->parameters_) saved_.insert(saved_.end(), p.values, p.values + p.size);
  jtr_.swap(saved_jtr_);
  jtj_.swap(saved_jtj_);
  jacobian_.swap(saved_jacobian_);
  residual_.swap(saved_residual_);
  pair_values_.swap(saved_pair_values_);
}

void DlsSolver::Restore() {
  size_t i = 0;
  for (auto& p : problem_->parameters_) {
    for (int k = 0; k < p.size; ++k) p.values[k] = saved_[i++];
  }
  jtr_.swap(saved_jtr_);
  jtj_.swap(saved_jtj_);
  jacobian_.swap(saved_jacobian_);
  residual_.swap(saved_residual_);
  pair_values_.swap(saved_pair_values_);
}

bool DlsSolver::ApplyStep(const Eigen::VectorXd& delta, double* step_norm, double* x_norm) {
  *step_norm = delta.norm();
  double x_sq = 0.0;
  for (auto& p : problem_->parameters_) {
    for (int k = 0; k < p.size; ++k) x_sq += p.values[k] * p.values[k];
    if (p.constant) continue;
    const double* d = delta.data() + p.tangent_offset;
    if (p.manifold == nullptr) {
      for (int k = 0; k < p.size; ++k) p.values[k] += d[k];
    } else {
      plus_.resize(p.size);
      if (!p.manifold->Plus(p.values, d, plus_.data())) return false;
      for (int k = 0; k < p.size; ++k) p.values[k] = plus_[k];
    }
  }
  *x_norm = std::sqrt(x_sq);
  return true;
}

double DlsSolver::MaxGradient() const { return jtr_.cwiseAbs().maxCoeff(); }

bool DlsSolver::ComputeStep(double lambda, Eigen::VectorXd* delta) {
  const auto start = std::chrono::steady_clock::now();
  const bool solved = SolveLinearSystem(lambda, delta);
  linear_solve_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return solved;
}

bool DlsSolver::SolveLinearSystem(double lambda, Eigen::VectorXd* delta) {
  if (linear_solver_ == DlsLinearSolver::kSparseLdlt) {
    double* values = sparse_.valuePtr();
    for (size_t k = 0; k < gather_.size(); ++k) values[k] = pair_values_[gather_[k]];
    for (const Eigen::Index k : diagonal_) values[k] += lambda;
    ldlt_.factorize(sparse_);
    if (ldlt_.info() != Eigen::Success) return false;
    *delta = ldlt_.solve(-jtr_);
    return true;
  }
  if (linear_solver_ == DlsLinearSolver::kBlockBanded) {
    band_.SetZero();
    double* values = band_.data();
    for (size_t e = 0; e < scatter_.size(); ++e) {
      if (scatter_[e] >= 0) values[scatter_[e]] = pair_values_[e];
    }
    const int n = band_.block_size();
    for (int k = 0; k < band_.num_blocks(); ++k) {
      Eigen::Map<Eigen::MatrixXd>(band_.Block(k, 0), n, n).diagonal().array() += lambda;
    }
    if (!band_.Factorize()) return false;
    band_.Solve(-jtr_, delta);
    return true;
  }
  if (dense_j_) {
    system_.noalias() = jacobian_ * jacobian_.transpose();
    system_.diagonal().array() += lambda;
    Eigen::LLT<Eigen::MatrixXd> llt(system_);  // SPD: lambda > 0.
    delta->noalias() = jacobian_.transpose() * llt.solve(-residual_);
  } else {
    system_ = jtj_.selfadjointView<Eigen::Upper>();
    system_.diagonal().array() += lambda;
    Eigen::LLT<Eigen::MatrixXd> llt(system_);  // SPD: J^T J + lambda I, lambda > 0.
    *delta = llt.solve(-jtr_);
  }
  return true;  // A failed factorization shows as a non-finite step (as it always has).
}

void DlsSolver::Setup(DlsProblem* problem) {
  num_cols_ = 0;
  for (auto& p : problem->parameters_) {
    p.tangent_offset = p.constant ? -1 : num_cols_;
    if (!p.constant) num_cols_ += p.tangent_size;
  }
  num_rows_ = 0;
  for (const auto& r : problem->residuals_) num_rows_ += r.cost->num_residuals();
  // Eq. 4 as written (m x m system) when there are fewer residuals than unknowns.
  dense_j_ = linear_solver_ == DlsLinearSolver::kDense && num_rows_ < num_cols_;
  if (linear_solver_ == DlsLinearSolver::kDense) return;

  // The pair blocks: every non-constant block's diagonal pair, then each residual's pairs.
  const int num_blocks = static_cast<int>(problem->parameters_.size());
  std::unordered_map<long long, int> slot_of_pair;
  pairs_.clear();
  pair_slot_.clear();
  residual_pairs_.clear();
  size_t total = 0;
  auto slot = [&](int a, int b) {
    const long long key = static_cast<long long>(a) * num_blocks + b;
    const auto found = slot_of_pair.find(key);
    if (found != slot_of_pair.end()) return found->second;
    const DlsProblem::Parameter& pa = problem->parameters_[a];
    const DlsProblem::Parameter& pb = problem->parameters_[b];
    pairs_.push_back({pa.tangent_offset, pb.tangent_offset, pa.tangent_size, pb.tangent_size, total});
    total += static_cast<size_t>(pa.tangent_size) * pb.tangent_size;
    slot_of_pair.emplace(key, static_cast<int>(pairs_.size()) - 1);
    return static_cast<int>(pairs_.size()) - 1;
  };
  for (int a = 0; a < num_blocks; ++a) {
    if (!problem->parameters_[a].constant) slot(a, a);
  }
  for (const DlsProblem::Residual& block : problem->residuals_) {
    residual_pairs_.push_back(pair_slot_.size());
    for (const int a : block.blocks) {
      const DlsProblem::Parameter& pa = problem->parameters_[a];
      if (pa.constant) continue;
      for (const int b : block.blocks) {
        const DlsProblem::Parameter& pb = problem->parameters_[b];
        if (pb.constant || pb.tangent_offset < pa.tangent_offset) continue;
        pair_slot_.push_back(slot(a, b));
      }
    }
  }
  pair_values_.assign(total, 0.0);
  saved_pair_values_.assign(total, 0.0);

  if (linear_solver_ == DlsLinearSolver::kSparseLdlt) {
    // The upper triangle's pattern; each value first holds the index of its source entry.
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(total);
    for (const PairBlock& p : pairs_) {
      for (int c = 0; c < p.cols; ++c) {
        for (int r = 0; r < p.rows; ++r) {
          if (p.row + r > p.col + c) continue;  // Lower half of a diagonal block.
          triplets.emplace_back(p.row + r, p.col + c, static_cast<double>(p.offset + c * p.rows + r));
        }
      }
    }
    sparse_.resize(num_cols_, num_cols_);
    sparse_.setFromTriplets(triplets.begin(), triplets.end());
    sparse_.makeCompressed();
    gather_.resize(sparse_.nonZeros());
    for (Eigen::Index k = 0; k < sparse_.nonZeros(); ++k) gather_[k] = static_cast<size_t>(sparse_.valuePtr()[k]);
    diagonal_.resize(num_cols_);
    for (int c = 0; c < num_cols_; ++c) {
      // Rows sorted within a column; the diagonal is the column's last upper entry.
      diagonal_[c] = sparse_.outerIndexPtr()[c + 1] - 1;
      CHECK_EQ(sparse_.innerIndexPtr()[diagonal_[c]], c);
    }
    ldlt_.analyzePattern(sparse_);
    return;
  }

  // kBlockBanded.
  const int n = band_block_columns_;
  CHECK_EQ(num_cols_ % n, 0) << "tangent columns are not a multiple of the band block";
  int bandwidth = 0;
  for (const PairBlock& p : pairs_) {
    bandwidth = std::max(bandwidth, (p.col + p.cols - 1) / n - p.row / n);
  }
  band_.Resize(num_cols_ / n, n, bandwidth);
  scatter_.assign(total, -1);
  for (const PairBlock& p : pairs_) {
    for (int c = 0; c < p.cols; ++c) {
      for (int r = 0; r < p.rows; ++r) {
        const int i = p.row + r, j = p.col + c;  // Upper entry (i, j): lower (j, i).
        if (i > j) continue;
        const int row_block = j / n, d = row_block - i / n;
        scatter_[p.offset + c * p.rows + r] =
            (band_.Block(row_block, d) - band_.data()) + static_cast<std::ptrdiff_t>(i % n) * n + j % n;
      }
    }
  }
}

void DlsSolver::Solve(const DlsOptions& options, DlsProblem* problem, DlsSummary* summary) {
  Setup(problem);
  linear_solve_seconds_ = 0.0;
  problem_ = problem;
  RunDlsIterations(options, this, summary);
  problem_ = nullptr;
}

bool DlsSolver::NormalEquations(DlsProblem* problem, Eigen::SparseMatrix<double>* jtj, Eigen::VectorXd* jtr,
                                double* cost) {
  Setup(problem);
  const bool saved_dense_j = dense_j_;
  dense_j_ = false;  // The normal form, whatever the solve would use.
  problem_ = problem;
  const bool ok = Evaluate(true, cost);
  problem_ = nullptr;
  dense_j_ = saved_dense_j;
  if (!ok) return false;
  *jtr = jtr_;
  std::vector<Eigen::Triplet<double>> triplets;
  if (linear_solver_ == DlsLinearSolver::kDense) {
    for (int c = 0; c < num_cols_; ++c) {
      for (int r = 0; r <= c; ++r) {
        if (jtj_(r, c) == 0.0) continue;
        triplets.emplace_back(r, c, jtj_(r, c));
        if (r != c) triplets.emplace_back(c, r, jtj_(r, c));
      }
    }
  } else {
    for (const PairBlock& p : pairs_) {
      for (int c = 0; c < p.cols; ++c) {
        for (int r = 0; r < p.rows; ++r) {
          const int i = p.row + r, j = p.col + c;
          if (i > j) continue;
          const double v = pair_values_[p.offset + c * p.rows + r];
          triplets.emplace_back(i, j, v);
          if (i != j) triplets.emplace_back(j, i, v);
        }
      }
    }
  }
  jtj->resize(num_cols_, num_cols_);
  jtj->setFromTriplets(triplets.begin(), triplets.end());
  return true;
}

}  // namespace mocapsolve
