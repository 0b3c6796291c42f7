// A minimal SVG line plot, for the figures a person would rather look at than read
// (per-frame residuals of a solve, ...). No dependencies; NaN samples break the line.
#ifndef MOCAPSOLVE_IO_SVG_PLOT_H_
#define MOCAPSOLVE_IO_SVG_PLOT_H_

#include <string>
#include <vector>

namespace mocapsolve {

struct PlotSeries {
  std::string name;
  std::vector<double> y;  // Sample i is at x = i.
};

// An 800 x 360 SVG with axes, ticks, a legend and one polyline per series.
std::string LinePlotSvg(const std::string& title, const std::string& x_label,
                        const std::string& y_label, const std::vector<PlotSeries>& series);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_SVG_PLOT_H_
