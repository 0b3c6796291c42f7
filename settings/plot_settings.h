// --plot: the SVG figure a command also writes, each command declaring its own (solve: the
// per-frame marker residual; distance: the distance curves).
#ifndef MOCAPSOLVE_SETTINGS_PLOT_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_PLOT_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct PlotSetting {
  std::string plot;  // "" = none, or the figure's path (.svg).
};

const OptionGroup<PlotSetting>& SolvePlotOption();
const OptionGroup<PlotSetting>& DistancePlotOption();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_PLOT_SETTINGS_H_
