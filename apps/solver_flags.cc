#include "apps/solver_flags.h"

#include <glog/logging.h>

namespace {
// The flags' defaults are the settings' (pipeline/solver_settings.h): one source.
const mocapsolve::SolverSettings kDefault;
}  // namespace

DEFINE_string(solver, kDefault.solver.c_str(), "ceres | dls | dls_generic: who minimizes the (same) residual blocks "
              "(dls: the lean tree kernel; dls_generic: the generic DLS solver, a reference).");
DEFINE_string(mode, kDefault.mode.c_str(), "frame: solve frame by frame, warm-started; clip: then refine all "
              "frames as one sparse problem with smoothness (--clip_solver).");
DEFINE_string(linear_solver, kDefault.linear_solver.c_str(), "Ceres linear solver: dense_qr, dense_normal_cholesky, "
              "sparse_normal_cholesky, dense_schur, sparse_schur, iterative_schur, cgnr "
              "(default: dense_qr per frame, sparse_normal_cholesky per clip).");
DEFINE_string(trust_region, kDefault.trust_region.c_str(), "Ceres trust region: levenberg_marquardt | dogleg.");
DEFINE_int32(max_iterations, kDefault.max_iterations, "Iteration limit per solve (both solvers).");
DEFINE_double(function_tolerance, kDefault.function_tolerance, "Stop when the relative cost change is below this (Ceres' default).");
DEFINE_double(gradient_tolerance, kDefault.gradient_tolerance, "Stop when the max gradient entry is below this.");
DEFINE_double(parameter_tolerance, kDefault.parameter_tolerance, "Stop when the relative step is below this.");
DEFINE_int32(num_threads, kDefault.num_threads, "Threads: Ceres threads of the clip solve (per-frame solves use 1); "
             "repair runs its solves on two threads when >= 2. Speed only: a per-frame solve's result does not depend on it.");
DEFINE_string(loss, kDefault.loss.c_str(), "Robust loss on marker residuals: none | huber | cauchy.");
DEFINE_double(loss_scale, kDefault.loss_scale, "Where the loss bends, in skeleton length units.");
DEFINE_double(marker_weight, kDefault.marker_weight, "Weight of each marker residual.");
DEFINE_double(prior_weight, kDefault.prior_weight, "Per-frame pull of each joint rotation toward the previous "
              "frame's: a change of 1 radian costs as much as this many mm of marker error (in "
              "skeleton units when the skeleton's unit is unknown). It makes redundant chains "
              "(three spine joints seen by a few markers) well-posed, which cuts iterations "
              "several-fold at a tiny bias; 0 = off.");
DEFINE_double(rest_prior_weight, kDefault.rest_prior_weight, "Per-frame pull of each joint rotation toward the rest "
              "pose (the subject's mean pose when its file has one, as fit_skeleton and calibrate write; "
              "else zero local rotations), mm of marker error per radian like --prior_weight and well "
              "below it: it decides only directions no visible marker constrains (a joint's twist "
              "while its other marker is missing), which settle at the subject's typical pose instead of "
              "drifting; -1 (default): 5 toward the subject's mean pose, off when it has none; 0 = off.");
DEFINE_double(limit_weight, kDefault.limit_weight, "Soft joint limits (ASF 'limits'): 1 radian beyond a limit "
              "costs as much as this many mm of marker error; 0 = off (default: CMU's own solve "
              "of 02_01 leaves its ASF limits in 4.5% of dof samples, by up to 30 degrees).");
DEFINE_double(prior_translation_weight, kDefault.prior_translation_weight, "Per-frame pull of the root translation toward "
              "the previous frame's, per skeleton unit (0 = off).");
DEFINE_string(smooth_order, kDefault.smooth_order.c_str(), "Clip smoothness: velocity (faster: a block-tridiagonal "
              "system) | acceleration (keeps speed through the smoothing).");
DEFINE_string(sparse_library, kDefault.sparse_library.c_str(), "Clip solve's sparse Cholesky: eigen_sparse (faster "
              "here, and no GPL code) | suite_sparse (CHOLMOD).");
DEFINE_double(smooth_weight, kDefault.smooth_weight, "Clip smoothness weight of joint rotations, per radian of "
              "per-frame difference.");
DEFINE_double(smooth_translation_weight, kDefault.smooth_translation_weight, "Clip smoothness weight of the root translation, "
              "per skeleton unit of per-frame difference.");
DEFINE_double(clip_function_tolerance, kDefault.clip_function_tolerance, "Clip solve: stop when the relative cost change "
              "is below this (the whole-clip problem is large; its tail gains little).");
DEFINE_string(clip_solver, kDefault.clip_solver.c_str(), "Clip solve (--mode=clip): ceres (sparse Cholesky, "
              "--sparse_library) | dls (damped least squares on the same residuals, normal equations "
              "factored block-banded: one dense block per frame; --dls_lambda, --dls_damping).");
DEFINE_double(dls_lambda, kDefault.dls_lambda, "DLS damping: the initial (adaptive) or fixed lambda.");
DEFINE_string(dls_damping, kDefault.dls_damping.c_str(), "DLS damping: adaptive (Levenberg) | fixed (Buss).");

namespace mocapsolve {

SolverSettings SolverSettingsFromFlags() {
  SolverSettings s;
  s.solver = FLAGS_solver;
  s.mode = FLAGS_mode;
  s.linear_solver = FLAGS_linear_solver;
  s.trust_region = FLAGS_trust_region;
  s.max_iterations = FLAGS_max_iterations;
  s.function_tolerance = FLAGS_function_tolerance;
  s.gradient_tolerance = FLAGS_gradient_tolerance;
  s.parameter_tolerance = FLAGS_parameter_tolerance;
  s.num_threads = FLAGS_num_threads;
  s.loss = FLAGS_loss;
  s.loss_scale = FLAGS_loss_scale;
  s.marker_weight = FLAGS_marker_weight;
  s.prior_weight = FLAGS_prior_weight;
  s.prior_translation_weight = FLAGS_prior_translation_weight;
  s.rest_prior_weight = FLAGS_rest_prior_weight;
  s.limit_weight = FLAGS_limit_weight;
  s.smooth_order = FLAGS_smooth_order;
  s.smooth_weight = FLAGS_smooth_weight;
  s.smooth_translation_weight = FLAGS_smooth_translation_weight;
  s.clip_function_tolerance = FLAGS_clip_function_tolerance;
  s.sparse_library = FLAGS_sparse_library;
  s.clip_solver = FLAGS_clip_solver;
  s.dls_lambda = FLAGS_dls_lambda;
  s.dls_damping = FLAGS_dls_damping;
  s.verbose = FLAGS_v >= 1;
  return s;
}

Status MarkerSolveOptionsFromFlags(const LengthUnit& skeleton_unit, MarkerSolveOptions* options) {
  return MarkerSolveOptionsFromSettings(SolverSettingsFromFlags(), skeleton_unit, options);
}

Status ClipSolveOptionsFromFlags(ClipSolveOptions* options) {
  return ClipSolveOptionsFromSettings(SolverSettingsFromFlags(), options);
}

}  // namespace mocapsolve
