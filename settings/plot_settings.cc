#include "settings/plot_settings.h"

namespace mocapsolve {

const OptionGroup<PlotSetting>& SolvePlotOption() {
  static const OptionGroup<PlotSetting>* const group = &(*new OptionGroup<PlotSetting>()).Add(
      &PlotSetting::plot, "plot", "Write an SVG plot of the per-frame RMS marker residual to this file.");
  return *group;
}

const OptionGroup<PlotSetting>& DistancePlotOption() {
  static const OptionGroup<PlotSetting>* const group = &(*new OptionGroup<PlotSetting>()).Add(
      &PlotSetting::plot, "plot", "Write the distance curves (1 - weight) of every method and of --sweep as SVG.");
  return *group;
}

}  // namespace mocapsolve
