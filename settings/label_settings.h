// LabelSettings: the options of labelling raw marker points (`mocapsolve label`): the
// matching gates, the confidence below which a point stays unlabelled, and
// when the body counts as found or lost. Declared once; the CLI's flags. The labeller: problems/marker_label/marker_labeller.h; the task: tasks/label_task.h.
#ifndef MOCAPSOLVE_SETTINGS_LABEL_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_LABEL_SETTINGS_H_

#include "kinematics/status.h"
#include "kinematics/units.h"
#include "problems/marker_label/marker_labeller.h"
#include "settings/option.h"

namespace mocapsolve {

struct LabelSettings {
  double gate_mm = 25.0;             // Markers labelled in the previous frame (constant velocity).
  double reacquire_gate_mm = 60.0;   // Markers predicted by the model (after a gap).
  double acquire_gate_mm = 50.0;     // Finding the body: the final matching gate.
  double cluster_tolerance_mm = 30.0;  // Finding the body: rigid cluster distances.
  double min_confidence = 0.2;
  double accept_fraction = 0.85;
  double acquire_rms_mm = 15.0;
  double lost_fraction = 0.4;
  int acquire_frames = 60;
};

const OptionGroup<LabelSettings>& LabelSettingOptions();

// The labeller's options in the skeleton's unit (known: the gates are in mm), the marker
// solve's (priors) given.
Status LabellerOptionsFromSettings(const LabelSettings& settings, const LengthUnit& skeleton_unit,
                                   const MarkerSolveOptions& solve, LabellerOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_LABEL_SETTINGS_H_
