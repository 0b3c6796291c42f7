#include "solvers/block_banded_cholesky.h"

#include <random>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// A random symmetric matrix with block bandwidth b (random blocks inside the band), made
// positive definite by a diagonal shift that makes it diagonally dominant.
Eigen::MatrixXd RandomBandedSpd(int blocks, int n, int b, std::mt19937* rng) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const int size = blocks * n;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(size, size);
  for (int k = 0; k < blocks; ++k) {
    for (int d = 0; d <= b && d <= k; ++d) {
      for (int c = 0; c < n; ++c) {
        for (int r = 0; r < n; ++r) a((k * n) + r, (k - d) * n + c) = uniform(*rng);
      }
    }
  }
  Eigen::MatrixXd lower = a.triangularView<Eigen::Lower>();
  Eigen::MatrixXd spd = lower + lower.transpose();
  spd.diagonal().array() += 2.0 * n * (2 * b + 1);  // Diagonally dominant.
  return spd;
}

TEST(BlockBandedCholesky, SolvesLikeDenseCholesky) {
  std::mt19937 rng(1);
  for (int b : {1, 2, 3}) {
    const int blocks = 7, n = 5;
    const Eigen::MatrixXd a = RandomBandedSpd(blocks, n, b, &rng);
    BlockBandedCholesky band;
    band.Resize(blocks, n, b);
    for (int k = 0; k < blocks; ++k) {
      for (int d = 0; d <= b && d <= k; ++d) {
        Eigen::Map<Eigen::MatrixXd>(band.Block(k, d), n, n) = a.block(k * n, (k - d) * n, n, n);
      }
    }
    ASSERT_TRUE(band.Factorize());
    Eigen::VectorXd rhs = Eigen::VectorXd::NullaryExpr(blocks * n, [&] { return std::normal_distribution<>()(rng); });
    Eigen::VectorXd x;
    band.Solve(rhs, &x);
    const Eigen::VectorXd expected = a.llt().solve(rhs);
    // Well-conditioned (diagonally dominant): round-off only.
    EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm()) << "bandwidth " << b;
    // The diagonal factor blocks are the dense Cholesky's.
    const Eigen::MatrixXd l = a.llt().matrixL();
    const Eigen::MatrixXd lkk = Eigen::Map<Eigen::MatrixXd>(band.Block(blocks - 1, 0), n, n).triangularView<Eigen::Lower>();
    EXPECT_LT((lkk - l.bottomRightCorner(n, n)).norm(), 1e-12 * l.norm());
    const double n3 = n * n * n;
    EXPECT_DOUBLE_EQ(band.FactorizationFlops(), blocks * (n3 / 3 + 2 * b * n3 + b * (b - 1) * n3));
  }
}

TEST(BlockBandedCholesky, ReportsAMatrixThatIsNotPositiveDefinite) {
  BlockBandedCholesky band;
  band.Resize(3, 2, 1);
  for (int k = 0; k < 3; ++k) Eigen::Map<Eigen::Matrix2d>(band.Block(k, 0)).setIdentity();
  Eigen::Map<Eigen::Matrix2d>(band.Block(1, 1)) << 2.0, 0.0, 0.0, 0.0;  // Makes block 1's pivot 1 - 4 < 0.
  EXPECT_FALSE(band.Factorize());
}

}  // namespace
}  // namespace mocapsolve
