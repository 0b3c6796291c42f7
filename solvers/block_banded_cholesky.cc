#include "solvers/block_banded_cholesky.h"

#include <algorithm>

#include <Eigen/Cholesky>

namespace mocapsolve {

using BlockMap = Eigen::Map<Eigen::MatrixXd>;
using ConstBlockMap = Eigen::Map<const Eigen::MatrixXd>;

void BlockBandedCholesky::Resize(int num_blocks, int block_size, int bandwidth) {
  num_blocks_ = num_blocks;
  block_size_ = block_size;
  bandwidth_ = bandwidth;
  values_.assign(static_cast<size_t>(num_blocks) * (bandwidth + 1) * block_size * block_size, 0.0);
}

void BlockBandedCholesky::SetZero() { std::fill(values_.begin(), values_.end(), 0.0); }

bool BlockBandedCholesky::Factorize() {
  const int n = block_size_;
  for (int k = 0; k < num_blocks_; ++k) {
    const int reach = std::min(bandwidth_, k);  // Blocks L_{k, k-d}, d = 1..reach.
    // Off-diagonal blocks, farthest first: L_{k,i} needs L_{k,j} for j < i.
    for (int d = reach; d >= 1; --d) {
      const int i = k - d;
      BlockMap lki(Block(k, d), n, n);
      for (int e = d + 1; e <= reach; ++e) {  // J = k - e < i, and i - J = e - d <= b.
        lki.noalias() -= ConstBlockMap(Block(k, e), n, n) *
                         ConstBlockMap(Block(i, e - d), n, n).transpose();
      }
      const ConstBlockMap lii(Block(i, 0), n, n);
      lii.transpose().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(lki);
    }
    BlockMap diagonal(Block(k, 0), n, n);
    for (int d = 1; d <= reach; ++d) {
      diagonal.selfadjointView<Eigen::Lower>().rankUpdate(ConstBlockMap(Block(k, d), n, n), -1.0);
    }
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(diagonal);  // In place: lower triangle = L_kk.
    if (llt.info() != Eigen::Success) return false;
  }
  return true;
}

void BlockBandedCholesky::Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const {
  const int n = block_size_;
  if (x != &b) *x = b;
  // L y = b, block rows in order.
  for (int k = 0; k < num_blocks_; ++k) {
    auto xk = x->segment(static_cast<Eigen::Index>(k) * n, n);
    for (int d = 1; d <= std::min(bandwidth_, k); ++d) {
      xk.noalias() -= ConstBlockMap(Block(k, d), n, n) * x->segment(static_cast<Eigen::Index>(k - d) * n, n);
    }
    ConstBlockMap(Block(k, 0), n, n).triangularView<Eigen::Lower>().solveInPlace(xk);
  }
  // L^T x = y, block rows in reverse.
  for (int k = num_blocks_ - 1; k >= 0; --k) {
    auto xk = x->segment(static_cast<Eigen::Index>(k) * n, n);
    for (int d = 1; d <= std::min(bandwidth_, num_blocks_ - 1 - k); ++d) {
      xk.noalias() -= ConstBlockMap(Block(k + d, d), n, n).transpose() *
                      x->segment(static_cast<Eigen::Index>(k + d) * n, n);
    }
    ConstBlockMap(Block(k, 0), n, n).transpose().triangularView<Eigen::Upper>().solveInPlace(xk);
  }
}

double BlockBandedCholesky::FactorizationFlops() const {
  const double n3 = static_cast<double>(block_size_) * block_size_ * block_size_;
  const double b = bandwidth_;
  return num_blocks_ * (n3 / 3.0 + b * n3 + b * n3 + b * (b - 1.0) * n3);
}

}  // namespace mocapsolve
