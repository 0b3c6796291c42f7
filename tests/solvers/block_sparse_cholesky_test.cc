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

// Blocks of sizes 1-3 (ASF joints) padded in 3 x 3 storage: the same solution as a dense
// Cholesky of the unpadded matrix, and zeros in the padding.
TEST(BlockSparseCholesky, SolvesWithSmallerBlocks) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const int n = 9;
  const std::vector<int> sizes = {1, 3, 2, 1, 3, 2, 2, 1, 3};
  std::vector<int> offset(n + 1, 0);
  for (int b = 0; b < n; ++b) offset[b + 1] = offset[b] + sizes[b];
  const int m = offset[n];
  std::vector<std::pair<int, int>> pairs = {{1, 0}, {3, 1}, {4, 3}, {5, 3}, {8, 0}, {8, 4}, {7, 2}, {6, 5}, {8, 6}};
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(4 * m, m);
  for (int r = 0; r < j.rows(); ++r) {
    const auto& [a, b] = pairs[r % pairs.size()];
    for (int c = offset[a]; c < offset[a + 1]; ++c) j(r, c) = normal(rng);
    for (int c = offset[b]; c < offset[b + 1]; ++c) j(r, c) = normal(rng);
  }
  Eigen::MatrixXd dense = j.transpose() * j;
  dense.diagonal().array() += 0.1;
  BlockSparseCholesky cholesky;
  cholesky.Analyze(n, pairs, sizes);
  cholesky.SetZero();
  for (int b = 0; b < n; ++b) {
    Eigen::Matrix3d& d = cholesky.Diagonal(b);
    d.setIdentity();  // The padding.
    d.topLeftCorner(sizes[b], sizes[b]) = dense.block(offset[b], offset[b], sizes[b], sizes[b]);
  }
  for (size_t s = 0; s < pairs.size(); ++s) {
    const auto& [a, b] = pairs[s];
    cholesky.Block(static_cast<int>(s)).topLeftCorner(sizes[a], sizes[b]) =
        dense.block(offset[a], offset[b], sizes[a], sizes[b]);
  }
  ASSERT_TRUE(cholesky.Factorize());
  const Eigen::VectorXd rhs = Eigen::VectorXd::Random(m);
  Eigen::VectorXd padded = Eigen::VectorXd::Zero(3 * n), x;
  for (int b = 0; b < n; ++b) padded.segment(3 * b, sizes[b]) = rhs.segment(offset[b], sizes[b]);
  cholesky.Solve(padded, &x);
  const Eigen::VectorXd expected = dense.llt().solve(rhs);
  for (int b = 0; b < n; ++b) {
    // Same factorization in another order: round-off.
    EXPECT_LT((x.segment(3 * b, sizes[b]) - expected.segment(offset[b], sizes[b])).norm(), 1e-9) << "block " << b;
    EXPECT_EQ(x.segment(3 * b + sizes[b], 3 - sizes[b]).norm(), 0.0) << "block " << b;
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
