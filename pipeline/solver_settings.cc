#include "pipeline/solver_settings.h"

#include <algorithm>

#include <ceres/types.h>

namespace mocapsolve {

namespace {

Status CeresOptionsFromSettings(const SolverSettings& settings, ceres::Solver::Options* options) {
  if (!settings.linear_solver.empty() &&
      !ceres::StringToLinearSolverType(settings.linear_solver, &options->linear_solver_type)) {
    return Status::Error("--linear_solver: unknown '" + settings.linear_solver + "'");
  }
  if (!ceres::StringToTrustRegionStrategyType(settings.trust_region,
                                              &options->trust_region_strategy_type)) {
    return Status::Error("--trust_region: unknown '" + settings.trust_region + "'");
  }
  options->max_num_iterations = settings.max_iterations;
  options->function_tolerance = settings.function_tolerance;
  options->gradient_tolerance = settings.gradient_tolerance;
  options->parameter_tolerance = settings.parameter_tolerance;
  options->num_threads = settings.num_threads;
  if (settings.verbose) {  // Ceres prints every iteration (DLS logs through VLOG(1)).
    options->logging_type = ceres::PER_MINIMIZER_ITERATION;
    options->minimizer_progress_to_stdout = true;
  }
  std::string error;
  if (!options->IsValid(&error)) return Status::Error("Ceres options: " + error);
  return Status::Ok();
}

// The DLS iteration options both problems share; function_tolerance is the problem's.
Status DlsOptionsFromSettings(const SolverSettings& settings, double function_tolerance, DlsOptions* options) {
  options->max_iterations = settings.max_iterations;
  options->function_tolerance = function_tolerance;
  options->gradient_tolerance = settings.gradient_tolerance;
  options->parameter_tolerance = settings.parameter_tolerance;
  options->lambda = settings.dls_lambda;
  if (settings.dls_damping != "adaptive" && settings.dls_damping != "fixed") {
    return Status::Error("--dls_damping: unknown '" + settings.dls_damping + "' (adaptive, fixed)");
  }
  options->adaptive_damping = settings.dls_damping == "adaptive";
  return Status::Ok();
}

}  // namespace

Status MarkerSolveOptionsFromSettings(const SolverSettings& settings, const LengthUnit& skeleton_unit,
                                      MarkerSolveOptions* options) {
  if (!ParseSolverKind(settings.solver, &options->solver)) {
    return Status::Error("--solver: unknown '" + settings.solver + "' (ceres, dls, dls_generic)");
  }
  options->ceres = DefaultFrameCeresOptions();
  Status status = CeresOptionsFromSettings(settings, &options->ceres);
  if (!status.ok()) return status;
  options->ceres.num_threads = 1;  // Small dense problems: threads cost more than they give.
  status = DlsOptionsFromSettings(settings, settings.function_tolerance, &options->dls);
  if (!status.ok()) return status;
  options->marker_weight = settings.marker_weight;
  options->loss = settings.loss;
  options->loss_scale = settings.loss_scale;
  // Marker residuals are in skeleton units: express the prior's mm in them.
  options->prior_rotation_weight =
      skeleton_unit.known() ? settings.prior_weight / (1000.0 * skeleton_unit.metres_per_unit)
                            : settings.prior_weight;
  options->prior_translation_weight = settings.prior_translation_weight;
  if (!(settings.rest_prior_weight >= 0.0) && settings.rest_prior_weight != -1.0) {
    return Status::Error("--rest_prior_weight: expected >= 0, or -1 (auto)");
  }
  const bool rest_auto = settings.rest_prior_weight == -1.0;
  const double rest_mm = rest_auto ? kMeanPoseRestPriorWeight : settings.rest_prior_weight;
  options->rest_rotation_weight =
      skeleton_unit.known() ? rest_mm / (1000.0 * skeleton_unit.metres_per_unit) : rest_mm;
  options->rest_prior_needs_reference = rest_auto;
  options->limit_weight = skeleton_unit.known()
                              ? settings.limit_weight / (1000.0 * skeleton_unit.metres_per_unit)
                              : settings.limit_weight;
  std::string error;
  if (!options->IsValid(&error)) return Status::Error(error);
  return Status::Ok();
}

Status ClipSolveOptionsFromSettings(const SolverSettings& settings, ClipSolveOptions* options) {
  options->ceres = DefaultClipCeresOptions();
  Status status = CeresOptionsFromSettings(settings, &options->ceres);
  if (!status.ok()) return status;
  options->ceres.num_threads = std::max(settings.num_threads, 1);
  options->ceres.function_tolerance = settings.clip_function_tolerance;
  if (settings.clip_solver != "ceres" && settings.clip_solver != "dls") {
    return Status::Error("--clip_solver: unknown '" + settings.clip_solver + "' (ceres, dls)");
  }
  options->solver = settings.clip_solver;
  options->dls = DefaultClipDlsOptions();
  status = DlsOptionsFromSettings(settings, settings.clip_function_tolerance, &options->dls);
  if (!status.ok()) return status;
  if (!ceres::StringToSparseLinearAlgebraLibraryType(settings.sparse_library,
                                                     &options->ceres.sparse_linear_algebra_library_type)) {
    return Status::Error("--sparse_library: unknown '" + settings.sparse_library +
                         "' (eigen_sparse, suite_sparse)");
  }
  options->marker_weight = settings.marker_weight;
  options->loss = settings.loss;
  options->loss_scale = settings.loss_scale;
  if (settings.smooth_order == "velocity") {
    options->smoothness_order = SmoothnessOrder::kVelocity;
  } else if (settings.smooth_order == "acceleration") {
    options->smoothness_order = SmoothnessOrder::kAcceleration;
  } else {
    return Status::Error("--smooth_order: unknown '" + settings.smooth_order +
                         "' (velocity, acceleration)");
  }
  options->rotation_smoothness = settings.smooth_weight;
  options->translation_smoothness = settings.smooth_translation_weight;
  std::string error;
  if (!options->IsValid(&error)) return Status::Error(error);
  return Status::Ok();
}

}  // namespace mocapsolve
