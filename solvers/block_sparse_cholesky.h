// BlockSparseCholesky: A = L L^T for a symmetric positive definite matrix made of 3 x 3
// blocks, sparse at the block level (the normal equations of kinematic problems, where
// blocks (i, j) are non-zero only for joints on a common chain).
//
// Elimination follows the block index order (0 first); a caller puts the blocks that
// couple to many others last (for a skeleton: leaves first, root and root translation
// last, which gives no fill beyond the chains). Analyze() computes the fill (elimination
// tree) once for a pattern; Factorize() and Solve() then reuse it: right-looking, with
// dense 3 x 3 block operations and every update's target precomputed, so a factorization
// costs sum over block columns of (#blocks in the column)^2 small matrix products.
//
// Usage: Analyze(n, pairs); per solve: SetZero(), fill Block(slot) (slot = index of the
// pair given to Analyze; the lower triangle of a diagonal block is read, the upper
// ignored) and Diagonal(i), Factorize(), Solve(b, &x).
//
// Smaller blocks (an ASF joint with one or two dofs): Analyze's `sizes` gives each block's
// size s (1-3, default 3); the block then lives in the top-left s x s (s x s_other) part of
// its 3 x 3 storage, and the caller keeps the rest of its diagonal block identity and of
// its off-diagonal blocks zero (its unknowns then come out 0). The products run on the
// blocks' true sizes (fixed-size kernels per size triple), so a hinge costs 1/27 of a
// full block update.
#ifndef MOCAPSOLVE_SOLVERS_BLOCK_SPARSE_CHOLESKY_H_
#define MOCAPSOLVE_SOLVERS_BLOCK_SPARSE_CHOLESKY_H_

#include <utility>
#include <vector>

#include <Eigen/Core>

namespace mocapsolve {

class BlockSparseCholesky {
 public:
  // `pairs` (i, j), i > j, are the off-diagonal non-zero blocks of the lower triangle
  // (duplicates allowed); every diagonal block is implied.
  void Analyze(int num_blocks, const std::vector<std::pair<int, int>>& pairs,
               const std::vector<int>& sizes = {});

  int num_blocks() const { return static_cast<int>(diagonal_.size()); }
  void SetZero();
  Eigen::Matrix3d& Block(int slot) { return values_[column_of_slot_[slot]][entry_of_slot_[slot]]; }
  Eigen::Matrix3d& Diagonal(int block) { return diagonal_[block]; }

  // False if A is not (numerically) positive definite.
  bool Factorize();
  // x = A^-1 b (b and x of size 3 num_blocks; may alias).
  void Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const;

  // Blocks of L below the diagonal (after fill), for tests and reports.
  int num_factor_blocks() const;

 private:
  std::vector<std::vector<int>> rows_;                // Per column: rows below, sorted.
  std::vector<std::vector<Eigen::Matrix3d>> values_;  // Per column: A, then L, blocks.
  std::vector<Eigen::Matrix3d> diagonal_;             // A_kk, then L_kk.
  std::vector<Eigen::Matrix3d> inverse_;              // L_kk^-1.
  std::vector<int> sizes_;                            // Per block, 1-3.
  std::vector<int> column_of_slot_, entry_of_slot_;
  // Per column k, for each pair (a >= b) of its entries: where L_a L_b^T is subtracted
  // (column index and entry, entry -1 = the diagonal block), flattened.
  std::vector<std::vector<int>> update_column_, update_entry_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_BLOCK_SPARSE_CHOLESKY_H_
