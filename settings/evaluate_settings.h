// EvaluateSettings: `mocapsolve evaluate`'s own knobs (the repair, solver and damage options
// are theirs: settings/repair_settings.h, solver_settings.h, corruption_settings.h),
// declared once: its flags and Python's evaluate() keywords.
#ifndef MOCAPSOLVE_SETTINGS_EVALUATE_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_EVALUATE_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct EvaluateSettings {
  int trials = 1;               // Damage draws (seeds --seed, +1, ...).
  double white_noise_mm = 0.0;  // small_errors: noise per axis before the damage, mm.
  // leave_one_out: where the subject comes from (tasks/evaluate_task.h): cross_take (as given,
  // fitted on another take) or time_split (fitted here on the take's first half).
  std::string protocol = "cross_take";
  int refine_offsets = 0;              // leave_one_out: offset refinements per left-out marker.
  double refine_prior_frames = 200.0;  // Their prior: the calibrated offset's weight, frames.
  // leave_one_out: the others' samples off the body (off_body_samples.h) left out of the
  // solve, with this tolerance, mm; 0 = off.
  double off_body_mm = 100.0;
};

const OptionGroup<EvaluateSettings>& EvaluateSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_EVALUATE_SETTINGS_H_
