#include "apps/solver_flags.h"

#include <ceres/types.h>
#include <glog/logging.h>

DEFINE_string(solver, "ceres", "ceres | dls | dls_generic: who minimizes the (same) residual blocks "
              "(dls: the lean tree kernel; dls_generic: the generic DLS solver, a reference).");
DEFINE_string(mode, "frame", "frame: solve frame by frame, warm-started; clip: then refine all "
              "frames as one sparse problem with smoothness (Ceres).");
DEFINE_string(linear_solver, "", "Ceres linear solver: dense_qr, dense_normal_cholesky, "
              "sparse_normal_cholesky, dense_schur, sparse_schur, iterative_schur, cgnr "
              "(default: dense_qr per frame, sparse_normal_cholesky per clip).");
DEFINE_string(trust_region, "levenberg_marquardt", "Ceres trust region: levenberg_marquardt | dogleg.");
DEFINE_int32(max_iterations, 50, "Iteration limit per solve (both solvers).");
DEFINE_double(function_tolerance, 1e-6, "Stop when the relative cost change is below this (Ceres' default).");
DEFINE_double(gradient_tolerance, 1e-10, "Stop when the max gradient entry is below this.");
DEFINE_double(parameter_tolerance, 1e-8, "Stop when the relative step is below this.");
DEFINE_int32(num_threads, 2, "Ceres threads for the clip solve (per-frame solves use 1).");
DEFINE_string(loss, "none", "Robust loss on marker residuals: none | huber | cauchy.");
DEFINE_double(loss_scale, 1.0, "Where the loss bends, in skeleton length units.");
DEFINE_double(marker_weight, 1.0, "Weight of each marker residual.");
DEFINE_double(prior_weight, 20.0, "Per-frame pull of each joint rotation toward the previous "
              "frame's: a change of 1 radian costs as much as this many mm of marker error (in "
              "skeleton units when the skeleton's unit is unknown). It makes redundant chains "
              "(three spine joints seen by a few markers) well-posed, which cuts iterations "
              "several-fold at a tiny bias; 0 = off.");
DEFINE_double(limit_weight, 0.0, "Soft joint limits (ASF 'limits'): 1 radian beyond a limit "
              "costs as much as this many mm of marker error; 0 = off (default: CMU's own solve "
              "of 02_01 leaves its ASF limits in 4.5% of dof samples, by up to 30 degrees).");
DEFINE_double(prior_translation_weight, 0.0, "Per-frame pull of the root translation toward "
              "the previous frame's, per skeleton unit (0 = off).");
DEFINE_string(smooth_order, "velocity", "Clip smoothness: velocity (faster: a block-tridiagonal "
              "system) | acceleration (keeps speed through the smoothing).");
DEFINE_string(sparse_library, "eigen_sparse", "Clip solve's sparse Cholesky: eigen_sparse (faster "
              "here, and no GPL code) | suite_sparse (CHOLMOD).");
DEFINE_double(smooth_weight, 1.0, "Clip smoothness weight of joint rotations, per radian of "
              "per-frame difference.");
DEFINE_double(smooth_translation_weight, 0.1, "Clip smoothness weight of the root translation, "
              "per skeleton unit of per-frame difference.");
DEFINE_double(clip_function_tolerance, 1e-6, "Clip solve: stop when the relative cost change "
              "is below this (the whole-clip problem is large; its tail gains little).");
DEFINE_double(dls_lambda, 1e-3, "DLS damping: the initial (adaptive) or fixed lambda.");
DEFINE_string(dls_damping, "adaptive", "DLS damping: adaptive (Levenberg) | fixed (Buss).");

namespace mocapsolve {

const char* const kSolverFlagNames =
    "solver,mode,linear_solver,trust_region,max_iterations,function_tolerance,"
    "gradient_tolerance,parameter_tolerance,num_threads,loss,loss_scale,marker_weight,"
    "prior_weight,prior_translation_weight,limit_weight,smooth_order,smooth_weight,"
    "smooth_translation_weight,clip_function_tolerance,sparse_library,dls_lambda,dls_damping";

namespace {

Status CeresOptionsFromFlags(ceres::Solver::Options* options) {
  if (!FLAGS_linear_solver.empty() &&
      !ceres::StringToLinearSolverType(FLAGS_linear_solver, &options->linear_solver_type)) {
    return Status::Error("--linear_solver: unknown '" + FLAGS_linear_solver + "'");
  }
  if (!ceres::StringToTrustRegionStrategyType(FLAGS_trust_region,
                                              &options->trust_region_strategy_type)) {
    return Status::Error("--trust_region: unknown '" + FLAGS_trust_region + "'");
  }
  options->max_num_iterations = FLAGS_max_iterations;
  options->function_tolerance = FLAGS_function_tolerance;
  options->gradient_tolerance = FLAGS_gradient_tolerance;
  options->parameter_tolerance = FLAGS_parameter_tolerance;
  options->num_threads = FLAGS_num_threads;
  if (FLAGS_v >= 1) {  // --v=1: Ceres prints every iteration (DLS logs through VLOG(1)).
    options->logging_type = ceres::PER_MINIMIZER_ITERATION;
    options->minimizer_progress_to_stdout = true;
  }
  std::string error;
  if (!options->IsValid(&error)) return Status::Error("Ceres options: " + error);
  return Status::Ok();
}

}  // namespace

Status MarkerSolveOptionsFromFlags(const LengthUnit& skeleton_unit, MarkerSolveOptions* options) {
  if (!ParseSolverKind(FLAGS_solver, &options->solver)) {
    return Status::Error("--solver: unknown '" + FLAGS_solver + "' (ceres, dls, dls_generic)");
  }
  options->ceres = DefaultFrameCeresOptions();
  Status status = CeresOptionsFromFlags(&options->ceres);
  if (!status.ok()) return status;
  options->ceres.num_threads = 1;  // Small dense problems: threads cost more than they give.
  options->dls.max_iterations = FLAGS_max_iterations;
  options->dls.function_tolerance = FLAGS_function_tolerance;
  options->dls.gradient_tolerance = FLAGS_gradient_tolerance;
  options->dls.parameter_tolerance = FLAGS_parameter_tolerance;
  options->dls.lambda = FLAGS_dls_lambda;
  if (FLAGS_dls_damping != "adaptive" && FLAGS_dls_damping != "fixed") {
    return Status::Error("--dls_damping: unknown '" + FLAGS_dls_damping + "' (adaptive, fixed)");
  }
  options->dls.adaptive_damping = FLAGS_dls_damping == "adaptive";
  options->marker_weight = FLAGS_marker_weight;
  options->loss = FLAGS_loss;
  options->loss_scale = FLAGS_loss_scale;
  // Marker residuals are in skeleton units: express the prior's mm in them.
  options->prior_rotation_weight =
      skeleton_unit.known() ? FLAGS_prior_weight / (1000.0 * skeleton_unit.metres_per_unit)
                            : FLAGS_prior_weight;
  options->prior_translation_weight = FLAGS_prior_translation_weight;
  options->limit_weight = skeleton_unit.known()
                              ? FLAGS_limit_weight / (1000.0 * skeleton_unit.metres_per_unit)
                              : FLAGS_limit_weight;
  std::string error;
  if (!options->IsValid(&error)) return Status::Error(error);
  return Status::Ok();
}

Status ClipSolveOptionsFromFlags(ClipSolveOptions* options) {
  options->ceres = DefaultClipCeresOptions();
  Status status = CeresOptionsFromFlags(&options->ceres);
  if (!status.ok()) return status;
  options->ceres.num_threads = std::max(FLAGS_num_threads, 1);
  options->ceres.function_tolerance = FLAGS_clip_function_tolerance;
  if (!ceres::StringToSparseLinearAlgebraLibraryType(FLAGS_sparse_library,
                                                     &options->ceres.sparse_linear_algebra_library_type)) {
    return Status::Error("--sparse_library: unknown '" + FLAGS_sparse_library + "' (eigen_sparse, suite_sparse)");
  }
  options->marker_weight = FLAGS_marker_weight;
  options->loss = FLAGS_loss;
  options->loss_scale = FLAGS_loss_scale;
  if (FLAGS_smooth_order == "velocity") {
    options->smoothness_order = SmoothnessOrder::kVelocity;
  } else if (FLAGS_smooth_order == "acceleration") {
    options->smoothness_order = SmoothnessOrder::kAcceleration;
  } else {
    return Status::Error("--smooth_order: unknown '" + FLAGS_smooth_order + "' (velocity, acceleration)");
  }
  options->rotation_smoothness = FLAGS_smooth_weight;
  options->translation_smoothness = FLAGS_smooth_translation_weight;
  std::string error;
  if (!options->IsValid(&error)) return Status::Error(error);
  return Status::Ok();
}

}  // namespace mocapsolve
