// BlockSparseCholesky against a dense LLT on random SPD matrices with a tree-like block
// pattern plus cross links (fill), and a matrix that is not positive definite.
#include "solvers/block_sparse_cholesky.h"

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

TEST(BlockSparseCholesky, SolvesLikeADenseCholesky) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    const int n = 12 + trial;
    // A = sum of rank-3 terms J^T J over random "chains" (each touches a few blocks), so
    // the pattern is that of a kinematic normal matrix, plus a ridge.
    Eigen::MatrixXd dense = 0.1 * Eigen::MatrixXd::Identity(3 * n, 3 * n);
    std::vector<std::pair<int, int>> pairs;
    for (int term = 0; term < 3 * n; ++term) {
      std::vector<int> blocks = {static_cast<int>(rng() % n)};
      for (int k = 0; k < 3; ++k) blocks.push_back(std::min(n - 1, blocks.back() + 1 + static_cast<int>(rng() % 3)));
      if (term % 5 == 0) blocks.push_back(static_cast<int>(rng() % n));  // A cross link.
      std::sort(blocks.begin(), blocks.end());
      blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
      Eigen::MatrixXd j = Eigen::MatrixXd::Zero(3, 3 * n);
      for (int b : blocks) {
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) j(r, 3 * b + c) = normal(rng);
        }
      }
      dense += j.transpose() * j;
      for (size_t a = 0; a < blocks.size(); ++a) {
        for (size_t b = 0; b < a; ++b) pairs.push_back({blocks[a], blocks[b]});
      }
    }
    BlockSparseCholesky cholesky;
    cholesky.Analyze(n, pairs);
    cholesky.SetZero();
    for (int i = 0; i < n; ++i) cholesky.Diagonal(i) = dense.block<3, 3>(3 * i, 3 * i);
    for (size_t s = 0; s < pairs.size(); ++s) {
      cholesky.Block(static_cast<int>(s)) = dense.block<3, 3>(3 * pairs[s].first, 3 * pairs[s].second);
    }
    ASSERT_TRUE(cholesky.Factorize());
    const Eigen::VectorXd rhs = Eigen::VectorXd::Random(3 * n);
    Eigen::VectorXd x;
    cholesky.Solve(rhs, &x);
    const Eigen::VectorXd expected = dense.llt().solve(rhs);
    // Same factorization in another order: round-off relative to the solution's size.
    EXPECT_LT((x - expected).norm(), 1e-9 * (1.0 + expected.norm())) << "trial " << trial;
    EXPECT_GE(cholesky.num_factor_blocks(), 1);
  }
}

TEST(BlockSparseCholesky, RejectsAnIndefiniteMatrix) {
  BlockSparseCholesky cholesky;
  cholesky.Analyze(2, {{1, 0}});
  cholesky.SetZero();
  cholesky.Diagonal(0) = Eigen::Matrix3d::Identity();
  cholesky.Diagonal(1) = Eigen::Matrix3d::Identity();
  cholesky.Block(0) = 2.0 * Eigen::Matrix3d::Identity();  // |off-diagonal| > diagonal.
  EXPECT_FALSE(cholesky.Factorize());
}

}  // namespace
}  // namespace mocapsolve
