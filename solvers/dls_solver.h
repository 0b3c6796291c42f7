// DlsSolver: the hand-written damped-least-squares path (thesis eq. 4, Buss 2004),
// consuming the same ceres::CostFunction residual blocks as the Ceres path, so that a
// comparison measures the solvers and not two models (DESIGN.md).
//
// Problem: minimize 1/2 sum_i rho_i(|r_i(x)|^2) over parameter blocks x_b, each Euclidean
// or on a ceres::Manifold (ambient Jacobians from the cost functions are mapped to the
// tangent with the manifold's PlusJacobian; steps are applied with its Plus).
//
// Step (J the stacked tangent Jacobian, m rows, n tangent columns, e = -r):
//   delta = J^T (J J^T + lambda I)^-1 e        when m <  n  (eq. 4 as written),
//   delta = (J^T J + lambda I)^-1 J^T e        when m >= n  (the same vector, smaller system;
//                                                             J^T J accumulated block-sparse).
// Linear algebra (DlsLinearSolver):
//   kDense       the form above whose system is smaller, dense, Eigen LLT (per-frame problems);
//   kSparseLdlt  always the normal form; J^T J stored sparse (its pattern: every pair of
//                parameter blocks some residual block shares, found once per Solve), factored
//                by Eigen's SimplicialLDLT with AMD ordering (large problems, e.g. a whole clip);
//   kBlockBanded the normal form on a BlockBandedCholesky (solvers/block_banded_cholesky.h):
//                the tangent columns, in parameter block order, are cut into equal blocks of
//                band_block_columns (a clip: one frame each); the bandwidth is read from the
//                pattern. Needs num_columns a multiple of band_block_columns.
// The sparse forms accumulate J^T J into one dense block per pair of parameter blocks
// (each residual block's pairs, upper triangle) and scatter them into the factorization's
// storage.
// Robust losses are applied by iteratively reweighted least squares: each block's
// residual and Jacobian are scaled by sqrt(rho'(s)), s = |r|^2 (Ceres adds a second-order
// correction that this path omits).
//
// Damping and stopping rules: solvers/dls_iterations.h (RunDlsIterations), shared with
// the tree kernel (solvers/tree_dls_solver.h).
#ifndef MOCAPSOLVE_SOLVERS_DLS_SOLVER_H_
#define MOCAPSOLVE_SOLVERS_DLS_SOLVER_H_

#include <string>
#include <vector>

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/SparseCholesky>

#include "solvers/block_banded_cholesky.h"

#include "solvers/dls_iterations.h"

namespace mocapsolve {

// The problem: parameter blocks the caller owns, residual blocks that point at them.
// Nothing is owned: cost functions, losses and manifolds must outlive the problem.
class DlsProblem {
 public:
  // Returns the block's index. manifold == nullptr: Euclidean.
  int AddParameterBlock(double* values, int size, const ceres::Manifold* manifold = nullptr);
  void SetParameterBlockConstant(int block);
  // `blocks` are parameter block indices in the cost function's order.
  void AddResidualBlock(const ceres::CostFunction* cost, const ceres::LossFunction* loss,
                        std::vector<int> blocks);
  void Clear();

  int num_parameter_blocks() const { return static_cast<int>(parameters_.size()); }
  int num_residual_blocks() const { return static_cast<int>(residuals_.size()); }

 private:
  friend class DlsSolver;
  struct Parameter {
    double* values;
    int size;
    int tangent_size;
    const ceres::Manifold* manifold;
    bool constant = false;
    int tangent_offset = -1;  // Column of the block in J; -1 if constant.
  };
  struct Residual {
    const ceres::CostFunction* cost;
    const ceres::LossFunction* loss;
    std::vector<int> blocks;
  };
  std::vector<Parameter> parameters_;
  std::vector<Residual> residuals_;
};

enum class DlsLinearSolver { kDense, kSparseLdlt, kBlockBanded };

// "dense", "sparse_ldlt", "block_banded"; false on an unknown name.
bool ParseDlsLinearSolver(const std::string& name, DlsLinearSolver* solver);

// Holds the workspace between solves, so per-frame use allocates once.
class DlsSolver : private DlsModel {
 public:
  explicit DlsSolver(DlsLinearSolver linear_solver = DlsLinearSolver::kDense, int band_block_columns = 0);

  void Solve(const DlsOptions& options, DlsProblem* problem, DlsSummary* summary);

  // The cost and the normal equations at the problem's current parameters, as the solver
  // forms them (losses by IRLS): jtj the full symmetric J^T J (tangent columns in block
  // order), jtr = J^T r. For tests; false if a cost function fails.
  bool NormalEquations(DlsProblem* problem, Eigen::SparseMatrix<double>* jtj, Eigen::VectorXd* jtr,
                       double* cost);
  // Wall seconds the last Solve spent in ComputeStep (forming and factoring the system).
  double linear_solve_seconds() const { return linear_solve_seconds_; }
  // Flops of one factorization with kBlockBanded (after a Solve), else 0.
  double BandFactorizationFlops() const {
    return linear_solver_ == DlsLinearSolver::kBlockBanded ? band_.FactorizationFlops() : 0.0;
  }

 private:
  // DlsModel on problem_: the cost, and if `linearize`, the gradient J^T r and either J^T J
  // (normal form) or the dense J (dense_j_). False if a cost function fails.
  bool Evaluate(bool linearize, double* cost) override;
  int num_columns() const override { return num_cols_; }
  double MaxGradient() const override;
  bool ComputeStep(double lambda, Eigen::VectorXd* delta) override;
  bool SolveLinearSystem(double lambda, Eigen::VectorXd* delta);
  void Save() override;
  void Restore() override;
  bool ApplyStep(const Eigen::VectorXd& delta, double* step_norm, double* x_norm) override;

  // Columns, form (dense_j_) and, for the sparse forms, the pattern of problem.
  void Setup(DlsProblem* problem);

  DlsLinearSolver linear_solver_;
  int band_block_columns_;
  double linear_solve_seconds_ = 0.0;
  DlsProblem* problem_ = nullptr;
  bool dense_j_ = false;
  Eigen::MatrixXd system_;
  int num_rows_ = 0;
  int num_cols_ = 0;
  Eigen::MatrixXd jtj_;
  Eigen::VectorXd jtr_;
  Eigen::MatrixXd jacobian_;  // Dense J (m < n form only).
  Eigen::VectorXd residual_;
  std::vector<double> saved_;
  Eigen::MatrixXd saved_jtj_, saved_jacobian_;
  Eigen::VectorXd saved_jtr_, saved_residual_;
  // Scratch for one residual block.
  std::vector<double> r_;
  std::vector<std::vector<double>> ambient_;
  std::vector<Eigen::MatrixXd> tangent_;
  std::vector<double> plus_;  // A manifold's Plus output.
  std::vector<double> plus_jacobians_;  // Every manifold block's PlusJacobian, row-major.
  std::vector<size_t> plus_offset_;     // Where each block's starts.
  // Sparse forms: one dense block (column-major) per pair of parameter blocks a <= b (by
  // column) in pair_values_; per residual block, the slots of its pairs in the order
  // Evaluate visits them (pair_slot_, from residual_pairs_[i]).
  struct PairBlock {
    int row, col, rows, cols;  // Tangent offsets and sizes.
    size_t offset;             // In pair_values_.
  };
  std::vector<PairBlock> pairs_;
  std::vector<int> pair_slot_;
  std::vector<size_t> residual_pairs_;
  std::vector<double> pair_values_, saved_pair_values_;
  // kSparseLdlt: the upper triangle; entry k of its values is pair_values_[gather_[k]].
  Eigen::SparseMatrix<double> sparse_;
  std::vector<size_t> gather_;
  std::vector<Eigen::Index> diagonal_;  // Value index of each diagonal entry.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper> ldlt_;
  // kBlockBanded: band_.data()[scatter_[e]] = pair_values_[e] (scatter_[e] = -1: the
  // lower half of a diagonal pair block, not stored).
  BlockBandedCholesky band_;
  std::vector<std::ptrdiff_t> scatter_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_DLS_SOLVER_H_
