#include "settings/synthetic_marker_settings.h"

namespace mocapsolve {

const OptionGroup<SyntheticMarkerSettings>& SyntheticMarkerOptions() {
  using S = SyntheticMarkerSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::noise_mm, "noise_mm", "mm",
           "Standard deviation of Gaussian noise added to each coordinate, in mm (converted into the output unit).",
           0.0)
      .Add(&S::seed, "seed", "", "Seed of the noise and of --markerset=auto:N (the same output for the same seed).")
      .Add(&S::units, "units",
           "Length unit of the written markers (mm, cm, m, in) when the skeleton's unit is known.",
           {"mm", "cm", "m", "in"});
  return *group;
}

}  // namespace mocapsolve
