// SyntheticMarkerSettings: how `mocapsolve markers` writes synthetic markers (noise, seed,
// output unit), declared once: its flags and Python's markers() keywords.
#ifndef MOCAPSOLVE_SETTINGS_SYNTHETIC_MARKER_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_SYNTHETIC_MARKER_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct SyntheticMarkerSettings {
  double noise_mm = 0.0;      // Standard deviation per coordinate, mm.
  int seed = 1;               // Of the noise and of an auto marker set.
  std::string units = "mm";   // Of the written markers when the skeleton's unit is known.
};

const OptionGroup<SyntheticMarkerSettings>& SyntheticMarkerOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_SYNTHETIC_MARKER_SETTINGS_H_
