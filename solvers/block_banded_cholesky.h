// BlockBandedCholesky: A = L L^T for a symmetric positive definite matrix of N x N dense
// blocks of equal size n (n x n each), block-banded with block bandwidth b: block (K, I)
// is zero when |K - I| > b. The normal equations of a whole-clip problem have this shape:
// one block per frame (that frame's tangent unknowns), smoothness coupling a frame to its
// b neighbours (b = 1 velocity: block-tridiagonal; b = 2 acceleration: pentadiagonal).
// The band fills completely (each block of L inside the band is dense), so this is the
// structure's limit for a frame-ordered elimination, at dense-matrix (BLAS-3) speed.
//
// Storage: per block row K, b + 1 column-major n x n blocks: entry 0 the diagonal block
// A_KK (its lower triangle is read), entry d the block A_{K, K-d} below the diagonal.
// Factorize() overwrites them with L (row by row, left-looking):
//   L_{K,I} = (A_{K,I} - sum_{J < I, K - J <= b} L_{K,J} L_{I,J}^T) L_{I,I}^-T,  K - b <= I < K
//   L_{K,K} = chol(A_{K,K} - sum_{K - b <= J < K} L_{K,J} L_{K,J}^T)
// Flops (multiply and add counted apart) per block row:
//   n^3 / 3 (chol) + b n^3 (triangular solves) + b n^3 (diagonal updates)
//   + b (b - 1) n^3 (off-diagonal updates)  =  FactorizationFlops() / N.
// b = 1: 7/3 n^3 per block row; b = 2: 19/3 n^3.
#ifndef MOCAPSOLVE_SOLVERS_BLOCK_BANDED_CHOLESKY_H_
#define MOCAPSOLVE_SOLVERS_BLOCK_BANDED_CHOLESKY_H_

#include <vector>

#include <Eigen/Core>

namespace mocapsolve {

class BlockBandedCholesky {
 public:
  void Resize(int num_blocks, int block_size, int bandwidth);
  int num_blocks() const { return num_blocks_; }
  int block_size() const { return block_size_; }
  int bandwidth() const { return bandwidth_; }

  void SetZero();
  // Block (row, row - d), 0 <= d <= bandwidth, d <= row; column-major n x n.
  double* Block(int row, int d) {
    return &values_[(static_cast<size_t>(row) * (bandwidth_ + 1) + d) * block_size_ * block_size_];
  }
  // Flattened storage (Block(row, d) + c * n + r is entry (r, c) of that block).
  double* data() { return values_.data(); }
  size_t size() const { return values_.size(); }

  // False if A is not (numerically) positive definite.
  bool Factorize();
  // x = A^-1 b (size N n; may alias).
  void Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const;

  double FactorizationFlops() const;

 private:
  const double* Block(int row, int d) const {
    return &values_[(static_cast<size_t>(row) * (bandwidth_ + 1) + d) * block_size_ * block_size_];
  }
  int num_blocks_ = 0, block_size_ = 0, bandwidth_ = 0;
  std::vector<double> values_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_BLOCK_BANDED_CHOLESKY_H_
