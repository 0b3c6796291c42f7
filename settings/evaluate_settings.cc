#include "settings/evaluate_settings.h"

namespace mocapsolve {

const OptionGroup<EvaluateSettings>& EvaluateSettingOptions() {
  using S = EvaluateSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::trials, "trials", "trials", "Damage draws to average over (seeds --seed, +1, ...).", 1, 1000)
      .Add(&S::white_noise_mm, "white_noise_mm", "mm",
           "--method=small_errors: white noise (mm per axis) added to every sample before the damage, and to the "
           "undamaged take the own detections come from (a noise-free synthetic take: 1).", 0.0);
  return *group;
}

}  // namespace mocapsolve
