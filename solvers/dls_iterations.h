// The damped-least-squares iteration, written once for every DLS path: the generic
// DlsSolver (solvers/dls_solver.h, any ceres::CostFunction blocks) and the tree kernel
// (solvers/tree_dls_solver.h, rows on a kinematic tree). A path supplies a DlsModel (its
// evaluation, linear algebra and retraction); RunDlsIterations supplies the damping, the
// acceptance test and the stopping rules, so two paths on one problem stop alike.
//
// Problem: minimize F(x) = 1/2 sum_i rho_i(|r_i(x)|^2). With J the tangent Jacobian and
// g = J^T r at the current x, each iteration solves
//   (J^T J + lambda I) delta = -g        (or J^T (J J^T + lambda I)^-1 (-r), the same vector)
// and retracts x <- Plus(x, delta).
//
// Damping: fixed (lambda stays options.lambda; every step is taken, as in Buss' DLS) or
// adaptive (Levenberg: a step that lowers the cost is taken and lambda *= lambda_decrease,
// otherwise it is rejected and lambda *= lambda_increase). A linear solve that fails
// (ComputeStep false: the system is numerically not positive definite) is a rejection
// under adaptive damping, a failure under fixed damping.
//
// Stopping rules, checked before (cost, gradient) or after (function, parameter) each
// iteration:
//   cost <= absolute_cost_tolerance                               (ABSOLUTE_COST)
//   max_k |g_k| <= gradient_tolerance (or no tangent columns)     (GRADIENT_TOLERANCE)
//   |cost_old - cost_new| <= function_tolerance * cost_old        (FUNCTION_TOLERANCE)
//   |delta| <= parameter_tolerance * (|x| + parameter_tolerance)  (PARAMETER_TOLERANCE)
//     |x|: the ambient parameter vector before the step
//   lambda > max_lambda after a rejection                         (FUNCTION_TOLERANCE)
//   iterations == max_iterations                                  (NO_CONVERGENCE)
// The trial point is linearized together with its cost (an accepted step, the common case,
// then needs one evaluation), except after the last allowed iteration, where only its
// cost is needed.
#ifndef MOCAPSOLVE_SOLVERS_DLS_ITERATIONS_H_
#define MOCAPSOLVE_SOLVERS_DLS_ITERATIONS_H_

#include <string>

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

// What a DLS path provides. The model holds the parameters, one linearization (the
// current one) and one saved copy of both.
class DlsModel {
 public:
  virtual ~DlsModel() = default;
  // The cost at the current parameters and, if `linearize`, J^T r and what ComputeStep
  // needs. False if the cost is not finite or an evaluation failed.
  virtual bool Evaluate(bool linearize, double* cost) = 0;
  // Number of tangent columns, and max_k |(J^T r)_k| of the current linearization.
  virtual int num_columns() const = 0;
  virtual double MaxGradient() const = 0;
  // The damped step of the current linearization; false if the linear solve failed.
  virtual bool ComputeStep(double lambda, Eigen::VectorXd* delta) = 0;
  // Save (swap out) the parameters and the linearization / bring them back.
  virtual void Save() = 0;
  virtual void Restore() = 0;
  // x <- Plus(x, delta); |delta| and |x| (before the step) for the parameter tolerance.
  virtual bool ApplyStep(const Eigen::VectorXd& delta, double* step_norm, double* x_norm) = 0;
};

void RunDlsIterations(const DlsOptions& options, DlsModel* model, DlsSummary* summary);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_DLS_ITERATIONS_H_
