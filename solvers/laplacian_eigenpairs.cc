#include "solvers/laplacian_eigenpairs.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>

namespace mocapsolve {
namespace {

Status InverseSqrtDegrees(const Eigen::VectorXd& degrees, Eigen::VectorXd* inv_sqrt) {
  inv_sqrt->resize(degrees.size());
  for (Eigen::Index i = 0; i < degrees.size(); ++i) {
    if (!(degrees[i] > 0.0) || !std::isfinite(degrees[i])) {
      return Status::Error("kernel row " + std::to_string(i) +
                           ": row sum is not positive (isolated frame; widen sigma)");
    }
    (*inv_sqrt)[i] = 1.0 / std::sqrt(degrees[i]);
  }
  return Status::Ok();
}

}  // namespace

Status DenseLaplacianEigenpairs(const Eigen::MatrixXd& kernel, int count,
                                LaplacianEigenpairs* result) {
  const int n = static_cast<int>(kernel.rows());
  if (n == 0 || kernel.cols() != n) return Status::Error("kernel: expected a non-empty square matrix");
  result->degrees = kernel.rowwise().sum();
  Eigen::VectorXd s;
  Status status = InverseSqrtDegrees(result->degrees, &s);
  if (!status.ok()) return status;
  const Eigen::MatrixXd a = s.asDiagonal() * kernel * s.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a);
  if (solver.info() != Eigen::Success) return Status::Error("kernel: dense eigensolver failed");
  // Eigen sorts A's eigenvalues ascending; L's ascending are A's descending.
  const int m = (count <= 0 || count >= n) ? n : count;
  result->eigenvalues.resize(m);
  result->eigenvectors.resize(n, m);
  for (int k = 0; k < m; ++k) {
    result->eigenvalues[k] = std::max(0.0, 1.0 - solver.eigenvalues()[n - 1 - k]);
    result->eigenvectors.col(k) = solver.eigenvectors().col(n - 1 - k);
  }
  result->lanczos_iterations = 0;
  return Status::Ok();
}

Status SparseLaplacianEigenpairs(const Eigen::SparseMatrix<double>& kernel, int count,
                                 int subspace, LaplacianEigenpairs* result) {
  const int n = static_cast<int>(kernel.rows());
  if (n == 0 || kernel.cols() != n) return Status::Error("kernel: expected a non-empty square matrix");
  if (count < 1 || count >= n) {
    return Status::Error("eigenpairs: the sparse solver needs 1 <= count < #frames (" +
                         std::to_string(n) + "), got " + std::to_string(count));
  }
  result->degrees = Eigen::VectorXd::Zero(n);
  for (int c = 0; c < kernel.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(kernel, c); it; ++it) {
      result->degrees[it.row()] += it.value();
    }
  }
  Eigen::VectorXd s;
  Status status = InverseSqrtDegrees(result->degrees, &s);
  if (!status.ok()) return status;
  Eigen::SparseMatrix<double> a = kernel;
  for (int c = 0; c < a.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, c); it; ++it) {
      it.valueRef() *= s[it.row()] * s[it.col()];
    }
  }
  int ncv = subspace > 0 ? subspace : std::max(2 * count + 1, count + 20);
  ncv = std::min(std::max(ncv, count + 2), n);
  Spectra::SparseSymMatProd<double> op(a);
  Spectra::SymEigsSolver<Spectra::SparseSymMatProd<double>> solver(op, count, ncv);
  solver.init();
  const int restarts = static_cast<int>(solver.compute(Spectra::SortRule::LargestAlge, 10000, 1e-10));
  if (solver.info() != Spectra::CompInfo::Successful) {
    return Status::Error("eigenpairs: Lanczos did not converge for " + std::to_string(count) +
                         " eigenpairs of " + std::to_string(n) +
                         " frames (try fewer eigenpairs, more knn or a wider sigma)");
  }
  // Spectra returns LargestAlge in descending order of mu, i.e. ascending lambda.
  result->eigenvalues = (1.0 - solver.eigenvalues().array()).max(0.0).matrix();
  result->eigenvectors = solver.eigenvectors();
  result->lanczos_iterations = restarts;
  return Status::Ok();
}

}  // namespace mocapsolve
