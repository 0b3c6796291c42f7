// TakeSettings: a pipeline take's name, whether its points are labelled first, and the
// filter of its solved motion. Declared once:
// pipeline (and a batch manifest's per-take options).
#ifndef MOCAPSOLVE_SETTINGS_TAKE_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_TAKE_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct TakeSettings {
  std::string take_name;  // The characters' new animation; "" = the marker file's stem.
  int filter_levels = 0;  // Laplacian-pyramid bands dropped from the solved motion; 0 = none.
  // Labelling the take's points first (pipeline/take_labelling.h): "auto" when the file
  // lacks some of the subject's labels, "always", or "never" (the file's labels as they are).
  std::string label = "auto";
};

const OptionGroup<TakeSettings>& TakeSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_TAKE_SETTINGS_H_
