// SolverSettings: the marker solver's knobs as the user names them (one field per option,
// declared once in SolverOptions(): name, unit, help, check), and their one conversion into
// MarkerSolveOptions / ClipSolveOptions.
//
// The command line (apps/option_flags.h) makes its flags from the declarations, the Python
// module (python/) its keywords; both fill a SolverSettings and call the functions below,
// which check it against the declarations first, so defaults, validation and messages
// ("--solver: unknown 'x' (ceres, dls, dls_generic)") are one and the same.
#ifndef MOCAPSOLVE_SETTINGS_SOLVER_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_SOLVER_SETTINGS_H_

#include <string>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "kinematics/units.h"
#include "settings/option.h"
#include "problems/marker_solve/marker_clip_solver.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

// The pull toward the subject's mean pose, mm per radian, of a joint whose own markers are
// all missing in a frame (MarkerSolveOptions::hidden_rotation_weight): the markers of the
// bones below it alone would place it (a clavicle hinged on by the arm when its one shoulder
// marker is missing). Chosen by the leak-free leave-one-out (BENCHMARKS.md).
inline constexpr double kHiddenJointPriorWeight = 100.0;
// The pull toward the subject's mean pose, mm per radian, of a joint's twist about the line to
// its one observed marker while its other own markers are missing, where the markers below
// hardly observe that twist (MarkerSolveOptions::twist_rotation_weight): a foot that keeps
// its heel marker but not its toe marker turns freely about the heel one. Chosen by the
// leak-free leave-one-out (BENCHMARKS.md).
inline constexpr double kHiddenTwistPriorWeight = 100.0;

struct SolverSettings {
  std::string solver = "dls";              // dls | dls_generic | ceres.
  std::string mode = "frame";              // frame | clip (read by the callers).
  std::string linear_solver;               // Ceres' name; "" = the problem's default.
  std::string trust_region = "levenberg_marquardt";
  int max_iterations = 50;
  double function_tolerance = 1e-6;
  double gradient_tolerance = 1e-10;
  double parameter_tolerance = 1e-8;
  int num_threads = 2;                     // Clip solve's Ceres threads; repair's two threads when >= 2,
                                           // and a windowed take's retargets on a second thread.
  std::string loss = "none";               // none | huber | cauchy.
  double loss_scale = 1.0;                 // Skeleton units.
  double marker_weight = 1.0;
  double prior_weight = 20.0;              // mm of marker error per radian.
  double prior_translation_weight = 0.0;   // Per skeleton unit.
  double rest_prior_weight = -1.0;         // mm of marker error per radian away from rest; -1: auto
                                           // (kMeanPoseRestPriorWeight toward a mean pose, else off).
  double hidden_joint_prior_weight = kHiddenJointPriorWeight;  // mm/rad toward the mean pose of a
                                           // joint whose own markers are all missing; 0 = off.
  double hidden_twist_prior_weight = kHiddenTwistPriorWeight;  // mm/rad toward the mean pose of
                                           // a joint's twist about its one seen marker; 0 = off.
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

// The options, declared once (name, unit, help, check; the defaults are the fields'
// initializers above): the flags of every command that solves markers, the Python
// keywords of solve() and friends, the keys of config files and reports.
const OptionGroup<SolverSettings>& SolverOptions();

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
// A subject's per-frame options: the above in its skeleton's unit, with its mean pose (empty:
// none) as the rest prior's reference. Every solve of a subject's markers starts here, so no
// caller attaches the prior by hand.
Status MarkerSolveOptionsFromSettings(const SolverSettings& settings, const Skeleton& skeleton,
                                      const QuaternionVector& mean_pose, MarkerSolveOptions* options);
// Whole-clip options: clip_solver picks Ceres (linear_solver defaults to
// sparse_normal_cholesky) or the block-banded DLS (dls_lambda, dls_damping, the iteration
// limit and tolerances as per frame, clip_function_tolerance).
Status ClipSolveOptionsFromSettings(const SolverSettings& settings, ClipSolveOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_SOLVER_SETTINGS_H_
