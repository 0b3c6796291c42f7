#include "solvers/dls_iterations.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glog/logging.h>

namespace mocapsolve {

bool DlsOptions::IsValid(std::string* error) const {
  auto fail = [error](const char* message) {
    if (error != nullptr) *error = message;
    return false;
  };
  if (max_iterations < 0) return fail("max_iterations must be >= 0");
  if (!(lambda >= 0.0)) return fail("lambda must be >= 0");
  if (!adaptive_damping && !(lambda > 0.0)) return fail("fixed damping needs lambda > 0");
  if (!(lambda_increase > 1.0)) return fail("lambda_increase must be > 1");
  if (!(lambda_decrease > 0.0 && lambda_decrease < 1.0)) return fail("lambda_decrease must be in (0, 1)");
  if (!(min_lambda > 0.0 && max_lambda > min_lambda)) return fail("need 0 < min_lambda < max_lambda");
  if (function_tolerance < 0 || gradient_tolerance < 0 || parameter_tolerance < 0 ||
      absolute_cost_tolerance < 0) {
    return fail("tolerances must be >= 0");
  }
  return true;
}

std::string DlsSummary::BriefReport() const {
  static const char* kNames[] = {"FUNCTION_TOLERANCE", "GRADIENT_TOLERANCE",
                                 "PARAMETER_TOLERANCE", "ABSOLUTE_COST", "NO_CONVERGENCE",
                                 "FAILURE"};
  char buffer[256];
  std::snprintf(buffer, sizeof buffer,
                "DLS: cost %.6e -> %.6e, %d iterations (%d accepted), lambda %.2e, %s",
                initial_cost, final_cost, iterations, accepted_steps, final_lambda,
                kNames[static_cast<int>(termination)]);
  return buffer;
}

void RunDlsIterations(const DlsOptions& options, DlsModel* model, DlsSummary* summary) {
  *summary = DlsSummary();
  double cost = 0.0;
  if (!model->Evaluate(options.max_iterations > 0, &cost)) {
    summary->termination = DlsTermination::kFailure;
    return;
  }
  summary->initial_cost = summary->final_cost = cost;
  double lambda = options.adaptive_damping ? std::max(options.lambda, options.min_lambda) : options.lambda;
  Eigen::VectorXd delta;
  summary->termination = DlsTermination::kNoConvergence;
  while (summary->iterations < options.max_iterations) {
    if (cost <= options.absolute_cost_tolerance) {
      summary->termination = DlsTermination::kAbsoluteCost;
      break;
    }
    if (model->num_columns() == 0 || model->MaxGradient() <= options.gradient_tolerance) {
      summary->termination = DlsTermination::kGradientTolerance;
      break;
    }
    const bool solved = model->ComputeStep(lambda, &delta);
    ++summary->iterations;
    if (solved && !delta.allFinite()) {
      summary->termination = DlsTermination::kFailure;
      break;
    }
    bool accept = false;
    double step_norm = 0.0, x_norm = 0.0, new_cost = 0.0;
    if (solved) {
      model->Save();
      // Linearize at the trial point right away unless no iteration follows: accepted
      // steps (the common case) then need one evaluation instead of two; a rejected one
      // restores the old linearization.
      const bool evaluated =
          model->ApplyStep(delta, &step_norm, &x_norm) &&
          model->Evaluate(summary->iterations < options.max_iterations, &new_cost);
      accept = evaluated && (!options.adaptive_damping || new_cost < cost);
      if (!accept) model->Restore();
    }
    if (!accept) {
      VLOG(1) << "DLS iteration " << summary->iterations << ": rejected (cost " << new_cost
              << " >= " << cost << (solved ? "" : ", linear solve failed") << "), lambda "
              << lambda << " -> " << lambda * options.lambda_increase;
      if (!options.adaptive_damping) {
        summary->termination = DlsTermination::kFailure;
        break;
      }
      lambda *= options.lambda_increase;
      if (lambda > options.max_lambda) {
        summary->termination = DlsTermination::kFunctionTolerance;  // No step lowers the cost.
        break;
      }
      continue;
    }
    VLOG(1) << "DLS iteration " << summary->iterations << ": cost " << cost << " -> " << new_cost
            << ", lambda " << lambda << ", |step| " << step_norm;
    ++summary->accepted_steps;
    const double old_cost = cost;
    cost = new_cost;
    if (options.adaptive_damping) lambda = std::max(options.min_lambda, lambda * options.lambda_decrease);
    if (std::abs(old_cost - cost) <= options.function_tolerance * old_cost) {
      summary->termination = DlsTermination::kFunctionTolerance;
      break;
    }
    if (step_norm <= options.parameter_tolerance * (x_norm + options.parameter_tolerance)) {
      summary->termination = DlsTermination::kParameterTolerance;
      break;
    }
  }
  summary->final_cost = cost;
  summary->final_lambda = lambda;
}

}  // namespace mocapsolve
