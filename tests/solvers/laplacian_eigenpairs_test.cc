// Laplacian eigenpairs: the eigen-equation of L = I - D^-1/2 K D^-1/2, its null vector,
// dense against sparse (Spectra), and the bad-kernel errors.
#include "solvers/laplacian_eigenpairs.h"

#include <random>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// A Gaussian kernel on random points in 3-D: symmetric, positive, full.
Eigen::MatrixXd RandomKernel(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd points(n, 3);
  for (int i = 0; i < n; ++i) points.row(i) << normal(rng), normal(rng), normal(rng);
  Eigen::MatrixXd k(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) k(i, j) = std::exp(-(points.row(i) - points.row(j)).squaredNorm() / 2.0);
  }
  return k;
}

Eigen::MatrixXd Laplacian(const Eigen::MatrixXd& k) {
  const Eigen::VectorXd s = k.rowwise().sum().cwiseSqrt().cwiseInverse();
  return Eigen::MatrixXd::Identity(k.rows(), k.cols()) - s.asDiagonal() * k * s.asDiagonal();
}

TEST(LaplacianEigenpairs, DenseSolvesTheEigenEquation) {
  const Eigen::MatrixXd k = RandomKernel(40, 1);
  LaplacianEigenpairs e;
  ASSERT_TRUE(DenseLaplacianEigenpairs(k, 0, &e).ok());
  ASSERT_EQ(e.eigenvalues.size(), 40);
  const Eigen::MatrixXd l = Laplacian(k);
  for (int c = 0; c < 40; ++c) {
    // Residual of L phi = lambda phi; 1e-10 is far above Eigen's round-off on a 40 x 40.
    EXPECT_LT((l * e.eigenvectors.col(c) - e.eigenvalues[c] * e.eigenvectors.col(c)).norm(), 1e-10) << c;
    EXPECT_NEAR(e.eigenvectors.col(c).norm(), 1.0, 1e-12);
    if (c > 0) {
      EXPECT_LE(e.eigenvalues[c - 1], e.eigenvalues[c]);
    }
    EXPECT_GE(e.eigenvalues[c], 0.0);
    EXPECT_LE(e.eigenvalues[c], 2.0 + 1e-12);
  }
  // lambda_0 = 0 with phi_0 = D^1/2 1 / |D^1/2 1| (up to sign).
  EXPECT_NEAR(e.eigenvalues[0], 0.0, 1e-12);
  const Eigen::VectorXd phi0 = e.degrees.cwiseSqrt().normalized();
  EXPECT_NEAR(std::abs(phi0.dot(e.eigenvectors.col(0))), 1.0, 1e-12);
  EXPECT_LT((e.degrees - k.rowwise().sum()).norm(), 1e-12);

  LaplacianEigenpairs first;
  ASSERT_TRUE(DenseLaplacianEigenpairs(k, 5, &first).ok());
  ASSERT_EQ(first.eigenvalues.size(), 5);
  EXPECT_LT((first.eigenvalues - e.eigenvalues.head(5)).norm(), 1e-12);
}

TEST(LaplacianEigenpairs, SparseMatchesDense) {
  const Eigen::MatrixXd k = RandomKernel(60, 2);
  LaplacianEigenpairs dense, sparse;
  ASSERT_TRUE(DenseLaplacianEigenpairs(k, 0, &dense).ok());
  ASSERT_TRUE(SparseLaplacianEigenpairs(k.sparseView(), 6, 0, &sparse).ok());
  ASSERT_EQ(sparse.eigenvalues.size(), 6);
  ASSERT_EQ(sparse.eigenvectors.cols(), 6);
  for (int c = 0; c < 6; ++c) {
    // Lanczos converged to 1e-10 relative; the eigenvalues of a random kernel are simple.
    EXPECT_NEAR(sparse.eigenvalues[c], dense.eigenvalues[c], 1e-9) << c;
    EXPECT_NEAR(std::abs(sparse.eigenvectors.col(c).dot(dense.eigenvectors.col(c))), 1.0, 1e-7) << c;
  }
}

TEST(LaplacianEigenpairs, RejectsBadKernels) {
  Eigen::MatrixXd k = RandomKernel(10, 3);
  k.row(4).setZero();
  k.col(4).setZero();
  LaplacianEigenpairs e;
  Status status = DenseLaplacianEigenpairs(k, 0, &e);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("row 4"), std::string::npos) << status.message();
  EXPECT_FALSE(SparseLaplacianEigenpairs(k.sparseView(), 3, 0, &e).ok());
  EXPECT_FALSE(SparseLaplacianEigenpairs(RandomKernel(10, 4).sparseView(), 10, 0, &e).ok());
  EXPECT_FALSE(DenseLaplacianEigenpairs(Eigen::MatrixXd(3, 4), 0, &e).ok());
}

}  // namespace
}  // namespace mocapsolve
