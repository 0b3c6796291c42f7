#include "settings/solver_settings.h"

#include <algorithm>

#include <ceres/types.h>

namespace mocapsolve {

const OptionGroup<SolverSettings>& SolverOptions() {
  using S = SolverSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::solver, "solver",
           "dls | dls_generic | ceres: who minimizes the (same) residual blocks (dls, the default "
              "everywhere: the lean tree kernel, as accurate as Ceres at 3-10x the speed on every command "
              "measured; dls_generic: the generic DLS solver, a reference).",
           {"dls", "dls_generic", "ceres"})
      .Add(&S::mode, "mode",
           "frame: solve frame by frame, warm-started; clip: then refine all "
              "frames as one sparse problem with smoothness (--clip_solver).",
           {"frame", "clip"})
      .Add(&S::linear_solver, "linear_solver",
           "Ceres linear solver: dense_qr, dense_normal_cholesky, "
              "sparse_normal_cholesky, dense_schur, sparse_schur, iterative_schur, cgnr "
              "(default: dense_qr per frame, sparse_normal_cholesky per clip).",
           {"", "dense_qr", "dense_normal_cholesky", "sparse_normal_cholesky", "dense_schur", "sparse_schur", "iterative_schur", "cgnr"})
      .Add(&S::trust_region, "trust_region",
           "Ceres trust region: levenberg_marquardt | dogleg.",
           {"levenberg_marquardt", "dogleg"})
      .Add(&S::max_iterations, "max_iterations", "iterations",
           "Iteration limit per solve (both solvers).", 1)
      .Add(&S::function_tolerance, "function_tolerance", "",
           "Stop when the relative cost change is below this (Ceres' default).", 0)
      .Add(&S::gradient_tolerance, "gradient_tolerance", "",
           "Stop when the max gradient entry is below this.", 0)
      .Add(&S::parameter_tolerance, "parameter_tolerance", "",
           "Stop when the relative step is below this.", 0)
      .Add(&S::num_threads, "num_threads", "threads",
           "Threads: Ceres threads of the clip solve (per-frame solves use 1); "
             "repair runs its solves on two threads when >= 2, and pipeline, on a take over --window_frames, retargets "
             "each window on a second thread while it repairs the next (the same files as with 1). Speed only: a "
             "per-frame solve's result does not depend on it.", 1)
      .Add(&S::loss, "loss",
           "Robust loss on marker residuals: none | huber | cauchy.",
           {"none", "huber", "cauchy"})
      .Add(&S::loss_scale, "loss_scale", "skeleton units",
           "Where the loss bends, in skeleton length units.", 0)
      .Add(&S::marker_weight, "marker_weight", "",
           "Weight of each marker residual.", 0)
      .Add(&S::prior_weight, "prior_weight", "mm/rad",
           "Per-frame pull of each joint rotation toward the previous "
              "frame's: a change of 1 radian costs as much as this many mm of marker error (in "
              "skeleton units when the skeleton's unit is unknown). It makes redundant chains "
              "(three spine joints seen by a few markers) well-posed, which cuts iterations "
              "several-fold at a tiny bias; 0 = off.", 0)
      .Add(&S::prior_translation_weight, "prior_translation_weight", "1/skeleton unit",
           "Per-frame pull of the root translation toward "
              "the previous frame's, per skeleton unit (0 = off).", 0)
      .Add(&S::rest_prior_weight, "rest_prior_weight", "mm/rad",
           "Per-frame pull of each joint rotation toward the rest "
              "pose (the subject's mean pose when its file has one, as fit_skeleton and calibrate write; "
              "else zero local rotations), mm of marker error per radian like --prior_weight and well "
              "below it: it decides only directions no visible marker constrains (a joint's twist "
              "while its other marker is missing), which settle at the subject's typical pose instead of "
              "drifting; -1 (default): 5 toward the subject's mean pose, off when it has none; 0 = off.")
      .Add(&S::hidden_joint_prior_weight, "hidden_joint_prior_weight", "mm/rad",
           "Per-frame pull toward the subject's mean pose of a joint whose own markers are all "
              "missing in the frame (it replaces --rest_prior_weight on that joint then): only the "
              "markers of the bones below it would place it, e.g. a clavicle whose one shoulder marker "
              "is occluded, hinged on by the arm. Applies only with a subject's mean pose; 0 = off.", 0)
      .Add(&S::hidden_twist_prior_weight, "hidden_twist_prior_weight", "mm/rad",
           "Per-frame pull toward the subject's mean pose of the twist of a joint with two or more "
              "markers of its own of which only one is seen in the frame, about the line from the joint "
              "to that marker (the one direction it leaves free; --rest_prior_weight holds the others), "
              "e.g. a foot's turn about its heel marker while the toe marker is occluded; only where the "
              "markers of the bones below observe that twist by less than a tenth of this (after the "
              "joints below make up what they can: a humerus whose forearm hinges on it is left to the "
              "forearm). Applies only with a subject's mean pose; 0 = off.", 0)
      .Add(&S::limit_weight, "limit_weight", "mm/rad",
           "Soft joint limits (ASF 'limits'): 1 radian beyond a limit "
              "costs as much as this many mm of marker error; 0 = off (default: CMU's own solve "
              "of 02_01 leaves its ASF limits in 4.5% of dof samples, by up to 30 degrees).", 0)
      .Add(&S::smooth_order, "smooth_order",
           "Clip smoothness: velocity (faster: a block-tridiagonal "
              "system) | acceleration (keeps speed through the smoothing).",
           {"velocity", "acceleration"})
      .Add(&S::smooth_weight, "smooth_weight", "1/rad",
           "Clip smoothness weight of joint rotations, per radian of "
              "per-frame difference.", 0)
      .Add(&S::smooth_translation_weight, "smooth_translation_weight", "1/skeleton unit",
           "Clip smoothness weight of the root translation, "
              "per skeleton unit of per-frame difference.", 0)
      .Add(&S::clip_function_tolerance, "clip_function_tolerance", "",
           "Clip solve: stop when the relative cost change "
              "is below this (the whole-clip problem is large; its tail gains little).", 0)
      .Add(&S::sparse_library, "sparse_library",
           "Clip solve's sparse Cholesky: eigen_sparse (faster "
              "here, and no GPL code) | suite_sparse (CHOLMOD).",
           {"eigen_sparse", "suite_sparse"})
      .Add(&S::clip_solver, "clip_solver",
           "Clip solve (--mode=clip): ceres (sparse Cholesky, "
              "--sparse_library) | dls (damped least squares on the same residuals, normal equations "
              "factored block-banded: one dense block per frame; --dls_lambda, --dls_damping).",
           {"ceres", "dls"})
      .Add(&S::dls_lambda, "dls_lambda", "",
           "DLS damping: the initial (adaptive) or fixed lambda.", 0)
      .Add(&S::dls_damping, "dls_damping",
           "DLS damping: adaptive (Levenberg) | fixed (Buss).",
           {"adaptive", "fixed"});
  return *group;
}

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
  options->adaptive_damping = settings.dls_damping == "adaptive";
  return Status::Ok();
}

}  // namespace

Status MarkerSolveOptionsFromSettings(const SolverSettings& settings, const LengthUnit& skeleton_unit,
                                      MarkerSolveOptions* options) {
  Status checked = SolverOptions().Validate(settings);
  if (!checked.ok()) return checked;
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
  options->hidden_rotation_weight = skeleton_unit.known()
                                        ? settings.hidden_joint_prior_weight / (1000.0 * skeleton_unit.metres_per_unit)
                                        : settings.hidden_joint_prior_weight;
  options->twist_rotation_weight = skeleton_unit.known()
                                       ? settings.hidden_twist_prior_weight / (1000.0 * skeleton_unit.metres_per_unit)
                                       : settings.hidden_twist_prior_weight;
  options->limit_weight = skeleton_unit.known()
                              ? settings.limit_weight / (1000.0 * skeleton_unit.metres_per_unit)
                              : settings.limit_weight;
  std::string error;
  if (!options->IsValid(&error)) return Status::Error(error);
  return Status::Ok();
}

Status MarkerSolveOptionsFromSettings(const SolverSettings& settings, const Skeleton& skeleton,
                                      const QuaternionVector& mean_pose, MarkerSolveOptions* options) {
  Status status = MarkerSolveOptionsFromSettings(settings, skeleton.unit(), options);
  if (status.ok()) options->rest_rotations = mean_pose;
  return status;
}

Status ClipSolveOptionsFromSettings(const SolverSettings& settings, ClipSolveOptions* options) {
  Status checked = SolverOptions().Validate(settings);
  if (!checked.ok()) return checked;
  options->ceres = DefaultClipCeresOptions();
  Status status = CeresOptionsFromSettings(settings, &options->ceres);
  if (!status.ok()) return status;
  options->ceres.num_threads = std::max(settings.num_threads, 1);
  options->ceres.function_tolerance = settings.clip_function_tolerance;
  options->solver = settings.clip_solver;
  options->dls = DefaultClipDlsOptions();
  status = DlsOptionsFromSettings(settings, settings.clip_function_tolerance, &options->dls);
  if (!status.ok()) return status;
  // One of the declared choices (checked above), each a Ceres name.
  ceres::StringToSparseLinearAlgebraLibraryType(settings.sparse_library,
                                                &options->ceres.sparse_linear_algebra_library_type);
  options->marker_weight = settings.marker_weight;
  options->loss = settings.loss;
  options->loss_scale = settings.loss_scale;
  options->smoothness_order =
      settings.smooth_order == "acceleration" ? SmoothnessOrder::kAcceleration : SmoothnessOrder::kVelocity;
  options->rotation_smoothness = settings.smooth_weight;
  options->translation_smoothness = settings.smooth_translation_weight;
  std::string error;
  if (!options->IsValid(&error)) return Status::Error(error);
  return Status::Ok();
}

}  // namespace mocapsolve
