// EvaluateSettings: `mocapsolve evaluate`'s own knobs (the repair, solver and damage options
// are theirs: settings/repair_settings.h, solver_settings.h, corruption_settings.h),
// declared once: its flags and Python's evaluate() keywords.
#ifndef MOCAPSOLVE_SETTINGS_EVALUATE_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_EVALUATE_SETTINGS_H_

#include "settings/option.h"

namespace mocapsolve {

struct EvaluateSettings {
  int trials = 1;               // Damage draws (seeds --seed, +1, ...).
  double white_noise_mm = 0.0;  // small_errors: noise per axis before the damage, mm.
};

const OptionGroup<EvaluateSettings>& EvaluateSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_EVALUATE_SETTINGS_H_
