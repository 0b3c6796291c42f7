// Laplacian eigenpairs: the smallest eigenpairs of the symmetric normalized graph
// Laplacian of a kernel (similarity) matrix, for Green's functions and diffusion maps.
//
//   K: #N x #N symmetric, K_ij >= 0 (dense, or sparse with both triangles stored)
//   D = diag(r), r_i = sum_j K_ij > 0
//   A = D^-1/2 K D^-1/2,  L = I - A
//   L phi_k = lambda_k phi_k,  |phi_k| = 1,  lambda_0 = 0 <= lambda_1 <= ... <= 2
//
// phi_0 is D^1/2 1 / |D^1/2 1| for a connected graph. Dense: Eigen's
// SelfAdjointEigenSolver on A (all N pairs, or the first `count`). Sparse: Spectra's
// Lanczos (SymEigsSolver with SparseSymMatProd, SortRule::LargestAlge) for the `count`
// largest algebraic eigenvalues mu_k of A, i.e. the smallest lambda_k = 1 - mu_k of L.
#ifndef MOCAPSOLVE_SOLVERS_LAPLACIAN_EIGENPAIRS_H_
#define MOCAPSOLVE_SOLVERS_LAPLACIAN_EIGENPAIRS_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "kinematics/status.h"

namespace mocapsolve {

struct LaplacianEigenpairs {
  Eigen::VectorXd eigenvalues;   // lambda_k of L, ascending; #count.
  Eigen::MatrixXd eigenvectors;  // phi_k as columns; #N x #count.
  Eigen::VectorXd degrees;       // r (row sums of K); #N.
  int lanczos_iterations = 0;    // Sparse only: Spectra's restart count.
};

// count <= 0 or >= N: all N pairs. Fails when a row sum is not positive.
Status DenseLaplacianEigenpairs(const Eigen::MatrixXd& kernel, int count,
                                LaplacianEigenpairs* result);

// 1 <= count < N. `subspace`: Lanczos basis size (0 = min(N, max(2 count + 1, count + 20))).
// Fails when a row sum is not positive or Lanczos does not converge (message says so).
Status SparseLaplacianEigenpairs(const Eigen::SparseMatrix<double>& kernel, int count,
                                 int subspace, LaplacianEigenpairs* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_LAPLACIAN_EIGENPAIRS_H_
