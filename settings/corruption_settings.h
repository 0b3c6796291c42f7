// CorruptionSettings: the synthetic damage's knobs as the user names them (one field per
// flag of `mocapsolve corrupt` / `evaluate`, same names and defaults; distances in mm),
// and their one conversion into CorruptionOptions (signal/marker_corruption.h) in a
// length unit. The command line (apps/corruption_flags.cc) and the Python module both
// call it. Knows nothing of gflags.
#ifndef MOCAPSOLVE_SETTINGS_CORRUPTION_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_CORRUPTION_SETTINGS_H_

#include "kinematics/status.h"
#include "kinematics/units.h"
#include "signal/marker_corruption.h"
#include "settings/option.h"

namespace mocapsolve {

struct CorruptionSettings {
  int seed = 1;
  int gaps = 10;
  int gap_min = 10;               // Frames.
  int gap_max = 60;
  int cluster_gaps = 2;
  double cluster_radius_mm = 150.0;
  int fly_off_frames = 5;
  double fly_off_mm = 100.0;
  int swaps = 1;
  int swap_length = 30;
  double swap_radius_mm = 200.0;
  int noisy_markers = 2;
  int noise_length = 60;
  double noise_sigma_mm = 5.0;
  int swaps_in_gaps = 0;          // The kinds below are off unless asked for.
  int jitter_markers = 0;
  int jitter_length = 60;
  double jitter_mm = 20.0;
  int ghosts = 0;
  int ghost_length = 20;
  double ghost_mm = 30.0;
  int unlabels = 0;               // Runs whose samples leave their label for an unlabelled track.
  int unlabel_length = 30;        // Frames of each.
};

// The options, declared once (name, unit, help, check; the defaults are the fields'
// initializers above): the flags of corrupt and evaluate, Python's keywords.
const OptionGroup<CorruptionSettings>& CorruptionSettingOptions();

// Distances in mm converted to `unit` (which must be known).
Status CorruptionOptionsFromSettings(const CorruptionSettings& settings, const LengthUnit& unit,
                                     CorruptionOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_CORRUPTION_SETTINGS_H_
