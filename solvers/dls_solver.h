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
// Robust losses are applied by iteratively reweighted least squares: each block's
// residual and Jacobian are scaled by sqrt(rho'(s)), s = |r|^2 (Ceres adds a second-order
// correction that this path omits).
//
// Damping: fixed (lambda stays options.lambda; every step is taken, as in Buss' DLS) or
// adaptive (Levenberg: a step that lowers the cost is taken and lambda *= lambda_decrease,
// otherwise it is rejected and lambda *= lambda_increase).
//
// Stopping rules, checked after each iteration:
//   |cost_old - cost_new| <= function_tolerance * cost_old      (FUNCTION_TOLERANCE)
//   max_k |(J^T r)_k| <= gradient_tolerance                      (GRADIENT_TOLERANCE)
//   |delta| <= parameter_tolerance * (|x| + parameter_tolerance) (PARAMETER_TOLERANCE)
//   iterations == max_iterations                                  (NO_CONVERGENCE)
//   cost <= absolute_cost_tolerance                               (already converged)
#ifndef MOCAPSOLVE_SOLVERS_DLS_SOLVER_H_
#define MOCAPSOLVE_SOLVERS_DLS_SOLVER_H_

#include <string>
#include <vector>

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <Eigen/Core>

namespace mocapsolve {

struct DlsOptions {
  int max_iterations = 50;
  bool adaptive_damping = true;    // false: fixed lambda, every step taken (Buss).
  double lambda = 1e-3;            // Initial (adaptive) or fixed damping.
  double lambda_increase = 10.0;
  double lambda_decrease = 0.3;
  double min_lambda = 1e-12;
  double max_lambda = 1e12;
  double function_tolerance = 1e-10;
  double gradient_tolerance = 1e-12;
  double parameter_tolerance = 1e-10;
  double absolute_cost_tolerance = 0.0;

  bool IsValid(std::string* error) const;
};

enum class DlsTermination {
  kFunctionTolerance,
  kGradientTolerance,
  kParameterTolerance,
  kAbsoluteCost,
  kNoConvergence,
  kFailure,  // A cost function returned false, or the linear solve failed.
};

struct DlsSummary {
  double initial_cost = 0.0;  // 1/2 sum rho(|r|^2), as Ceres reports cost.
  double final_cost = 0.0;
  int iterations = 0;          // Linear solves.
  int accepted_steps = 0;
  DlsTermination termination = DlsTermination::kNoConvergence;
  double final_lambda = 0.0;

  bool IsSolutionUsable() const { return termination != DlsTermination::kFailure; }
  std::string BriefReport() const;
};

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

// Holds the workspace between solves, so per-frame use allocates once.
class DlsSolver {
 public:
  void Solve(const DlsOptions& options, DlsProblem* problem, DlsSummary* summary);

 private:
  // Evaluates cost, and if `linearize`, the gradient J^T r and either J^T J (normal form)
  // or the dense J. Returns false if a cost function fails.
  bool Evaluate(DlsProblem* problem, bool linearize, bool dense_j, double* cost);
  void SaveParameters(const DlsProblem& problem);
  void SaveLinearization();
  void RestoreLinearization();
  void RestoreParameters(DlsProblem* problem) const;
  bool ApplyStep(DlsProblem* problem, const Eigen::VectorXd& delta, double* step_norm,
                 double* x_norm);

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
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_DLS_SOLVER_H_
