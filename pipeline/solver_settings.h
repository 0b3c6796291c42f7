// SolverSettings: the marker solver's knobs as the user names them (one field per flag of
// `mocapsolve solve`, same name, same default, same units: mm for the prior and limit
// weights), and their one conversion into MarkerSolveOptions / ClipSolveOptions.
//
// The command line (apps/solver_flags.cc) fills a SolverSettings from its gflags, the
// Python module (python/) from keyword arguments, a config file through the flags; all
// of them then call the functions below, so defaults, validation and error messages
// ("--solver: unknown 'x' (ceres, dls)") are one and the same. Knows nothing of gflags.
#ifndef MOCAPSOLVE_PIPELINE_SOLVER_SETTINGS_H_
#define MOCAPSOLVE_PIPELINE_SOLVER_SETTINGS_H_

#include <string>

#include "kinematics/status.h"
#include "kinematics/units.h"
#include "problems/marker_solve/marker_clip_solver.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

struct SolverSettings {
  std::string solver = "ceres";            // ceres | dls.
  std::string mode = "frame";              // frame | clip (read by the callers).
  std::string linear_solver;               // Ceres' name; "" = the problem's default.
  std::string trust_region = "levenberg_marquardt";
  int max_iterations = 50;
  double function_tolerance = 1e-6;
  double gradient_tolerance = 1e-10;
  double parameter_tolerance = 1e-8;
  int num_threads = 2;                     // Clip solve's Ceres threads; repair's two threads when >= 2.
  std::string loss = "none";               // none | huber | cauchy.
  double loss_scale = 1.0;                 // Skeleton units.
  double marker_weight = 1.0;
  double prior_weight = 20.0;              // mm of marker error per radian.
  double prior_translation_weight = 0.0;   // Per skeleton unit.
  double rest_prior_weight = -1.0;         // mm of marker error per radian away from rest; -1: auto
                                           // (kMeanPoseRestPriorWeight toward a mean pose, else off).
  double limit_weight = 0.0;               // mm of marker error per radian past a limit.
  std::string smooth_order = "velocity";   // velocity | acceleration.
  double smooth_weight = 1.0;
  double smooth_translation_weight = 0.1;
  double clip_function_tolerance = 1e-6;
  std::string sparse_library = "eigen_sparse";  // eigen_sparse | suite_sparse.
  std::string clip_solver = "ceres";       // ceres | dls: who minimizes the clip problem.
  double dls_lambda = 1e-3;
  std::string dls_damping = "adaptive";    // adaptive | fixed.
  bool verbose = false;                    // Ceres prints every iteration (--v=1).
};

// The settings' names, comma-separated, in the order above (verbose excluded): the flags
// of `mocapsolve solve` they come from.
inline constexpr char kSolverSettingNames[] =
    "solver,mode,linear_solver,trust_region,max_iterations,function_tolerance,"
    "gradient_tolerance,parameter_tolerance,num_threads,loss,loss_scale,marker_weight,"
    "prior_weight,prior_translation_weight,rest_prior_weight,limit_weight,smooth_order,smooth_weight,"
    "smooth_translation_weight,clip_function_tolerance,sparse_library,clip_solver,dls_lambda,dls_damping";

// The rest prior's weight by default (rest_prior_weight = -1), mm per radian: toward the
// subject's mean pose when the solve is given one (MarkerSolveOptions::rest_rotations), off
// otherwise. Chosen by leave-one-marker-out on the five fitted takes (BENCHMARKS.md): 5
// lowers every figure of every take (1, 2 and 10 do too; 5 most often best) and each CMU
// subject's median on the other's take. Directions no marker constrains then settle at the
// subject's typical pose instead of wherever the solver's path left them.
inline constexpr double kMeanPoseRestPriorWeight = 5.0;

// Per-frame options (solver picks Ceres or DLS); the skeleton's unit converts the prior
// and limit weights from mm.
Status MarkerSolveOptionsFromSettings(const SolverSettings& settings, const LengthUnit& skeleton_unit,
                                      MarkerSolveOptions* options);
// Whole-clip options: clip_solver picks Ceres (linear_solver defaults to
// sparse_normal_cholesky) or the block-banded DLS (dls_lambda, dls_damping, the iteration
// limit and tolerances as per frame, clip_function_tolerance).
Status ClipSolveOptionsFromSettings(const SolverSettings& settings, ClipSolveOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_SOLVER_SETTINGS_H_
