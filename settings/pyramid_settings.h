// PyramidSettings: the Laplacian pyramid's knobs as users name them (--kernel_a, --tension),
// declared once for filter, bands, blend and pipeline and Python's pyramid functions, and
// their one conversion into PyramidOptions (signal/laplacian_pyramid.h).
#ifndef MOCAPSOLVE_SETTINGS_PYRAMID_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_PYRAMID_SETTINGS_H_

#include "kinematics/status.h"
#include "settings/option.h"
#include "signal/generating_kernel.h"
#include "signal/laplacian_pyramid.h"

namespace mocapsolve {

struct PyramidSettings {
  double kernel_a = GeneratingKernel().a;   // Centre weight of the 5-tap kernel, [0.25, 0.75].
  double tension = PyramidOptions().tension;  // Of EXPAND's Cardinal spline, [0, 1].
};

const OptionGroup<PyramidSettings>& PyramidSettingOptions();

// Validated (the message names the option); `levels` as PyramidOptions::levels.
Status PyramidOptionsFromSettings(const PyramidSettings& settings, int levels, PyramidOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_PYRAMID_SETTINGS_H_
