// RepairSettings: marker repair's knobs as the user names them (one field per flag of
// `mocapsolve repair`, same name, same default; thresholds in cm and degrees), and their
// one conversion into RepairOptions in the skeleton's units. The command line
// (apps/repair_flags.cc) and the Python module both call RepairOptionsFromSettings, so
// defaults, validation and messages are one. Knows nothing of gflags.
#ifndef MOCAPSOLVE_SETTINGS_REPAIR_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_REPAIR_SETTINGS_H_

#include <string>

#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "settings/solver_settings.h"
#include "problems/marker_repair/marker_repair.h"

namespace mocapsolve {

struct RepairSettings {
  double dp_max_cm = 10.0;           // Joint farther than this from the reference: bad.
  double dr_max_deg = 30.0;          // Joint turned more than this from the reference: bad.
  double outlier_cm = 4.0;           // Fixed outlier gate (outliers=fixed) and the robust gates' cap.
  std::string outliers = "robust";   // robust (per-marker median + MADs) | fixed (outlier_cm).
  double outlier_mads = 6.0;         // Robust gate: robust standard deviations past the median.
  double outlier_min_cm = 1.0;       // Robust gate's floor.
  bool undo_swaps = true;            // Relabel swapped samples instead of refilling them.
  double swap_radius_cm = 30.0;      // Labels whose predictions are this close may swap.
  int swap_min_frames = 2;           // Frames a swap must persist.
  bool assign_unlabelled = true;     // Unlabelled points become missing markers' samples.
  double unlabelled_min_cm = 2.0;    // Floor of the assignment gate around a marker's prediction.
  double unlabelled_max_cm = 5.0;    // Its cap.
  int unlabelled_min_frames = 3;     // Frames an assignment needs when it continues no observed sample.
  int trim_max = 120;                // Frames trimmed at most per side of a gap.
  int small_track = 120;             // Valid runs of at most this many frames are dropped.
  int small_gap = 5;                 // Gaps of at most this many frames: plain cubic.
  double vel_clamp = 0.25;           // cm per frame.
  int edge_samples = 1;              // Samples per gap edge its offset velocity is fitted to (1: none).
  std::string fill = "kriging";       // kriging (offset process, conditional mean) | blend (edge offsets blended).
  int fill_samples = 10;             // kriging: offset samples conditioned on per gap side.
  bool refit_reference = true;       // Tracker: X^ refitted without the cut samples for the fill.
  double refit_rough_factor = 3.0;   // Cut runs rougher than this (vs the marker's own) use X^ as solved.
  double rough_extension_factor = 6.0;  // Rough runs extended over neighbours this rough (0: off).
  bool carry_joints = true;          // Joints that lost their markers carried across the gap.
  std::string reference = "tracker";  // tracker | clip.
  std::string reference_loss = "cauchy";
  double reference_loss_cm = 1.0;
  double tracker_prior_weight = 20.0;     // mm per radian.
  double tracker_translation_prior = 0.0;
  double tracker_function_tolerance = 1e-4;
};

// The options, declared once (name, unit, help, check; the defaults are the fields'
// initializers above): the flags of repair, evaluate and pipeline, Python's keywords.
const OptionGroup<RepairSettings>& RepairSettingOptions();

// Repair solves every frame two or three times: its solver options are the solver's
// (SolverOptions) without --mode (repair has its own --reference); pipeline declares
// these too.
const OptionGroup<SolverSettings>& RepairSolverOptions();
// `evaluate`'s: RepairSolverOptions with --num_threads told in its terms (markers at once).
const OptionGroup<SolverSettings>& EvaluateSolverOptions();

// `solver` holds the naive solve's settings (RepairSolverOptions' defaults when the user
// did not choose). The skeleton's unit must be known.
Status RepairOptionsFromSettings(const RepairSettings& settings, const SolverSettings& solver,
                                 const Skeleton& skeleton, RepairOptions* options);

// A subject's mean pose (MarkerTake::mean_pose; empty: zero rotations) as the rest prior's
// reference of the repair's naive solve (the take's solve). The tracker reference has no
// rest prior (RepairOptionsFromSettings): it judges the samples.
void SetRepairRestRotations(const QuaternionVector& mean_pose, RepairOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_REPAIR_SETTINGS_H_
