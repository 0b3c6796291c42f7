// BlendSettings: `mocapsolve blend`'s transition window, where B starts and the multires
// blend's pyramid depth (--method: settings/method_settings.h; the pyramid's kernel:
// settings/pyramid_settings.h). Declared once.
#ifndef MOCAPSOLVE_SETTINGS_BLEND_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_BLEND_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct BlendSettings {
  std::string transition;  // START:END, frames of A (120:150) or seconds (1s:1.25s).
  int b_start = -1;        // Frame of A where B's frame 0 lies; -1: the transition start.
  int blend_levels = 4;    // 0 = as many as fit.
};

const OptionGroup<BlendSettings>& BlendSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_BLEND_SETTINGS_H_
