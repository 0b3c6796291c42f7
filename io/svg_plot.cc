#include "io/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace mocapsolve {
namespace {

std::string Escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

std::string Number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

}  // namespace

std::string LinePlotSvg(const std::string& title, const std::string& x_label,
                        const std::string& y_label, const std::vector<PlotSeries>& series) {
  const double width = 800, height = 360, left = 70, right = 20, top = 40, bottom = 50;
  double y_max = 0.0;
  size_t n = 1;
  for (const PlotSeries& s : series) {
    n = std::max(n, s.y.size());
    for (double v : s.y) {
      if (std::isfinite(v)) y_max = std::max(y_max, v);
    }
  }
  if (!(y_max > 0.0)) y_max = 1.0;
  const double x_scale = (width - left - right) / std::max<double>(1.0, static_cast<double>(n - 1));
  const double y_scale = (height - top - bottom) / y_max;
  auto px = [&](double x) { return left + x * x_scale; };
  auto py = [&](double y) { return height - bottom - y * y_scale; };
  static const char* kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd"};
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"800\" height=\"360\" "
                    "font-family=\"sans-serif\" font-size=\"12\">\n"
                    "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"400\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" + Escape(title) + "</text>\n";
  svg += "<line x1=\"" + Number(left) + "\" y1=\"" + Number(py(0)) + "\" x2=\"" + Number(width - right) +
         "\" y2=\"" + Number(py(0)) + "\" stroke=\"black\"/>\n";
  svg += "<line x1=\"" + Number(left) + "\" y1=\"" + Number(top) + "\" x2=\"" + Number(left) + "\" y2=\"" +
         Number(py(0)) + "\" stroke=\"black\"/>\n";
  for (int t = 0; t <= 4; ++t) {
    const double y = y_max * t / 4.0, x = (n - 1) * t / 4.0;
    svg += "<text x=\"" + Number(left - 6) + "\" y=\"" + Number(py(y) + 4) +
           "\" text-anchor=\"end\">" + Number(y) + "</text>\n";
    svg += "<line x1=\"" + Number(left) + "\" y1=\"" + Number(py(y)) + "\" x2=\"" + Number(width - right) +
           "\" y2=\"" + Number(py(y)) + "\" stroke=\"#ddd\"/>\n";
    svg += "<text x=\"" + Number(px(x)) + "\" y=\"" + Number(height - bottom + 16) +
           "\" text-anchor=\"middle\">" + Number(std::round(x)) + "</text>\n";
  }
  svg += "<text x=\"400\" y=\"" + Number(height - 12) + "\" text-anchor=\"middle\">" + Escape(x_label) + "</text>\n";
  svg += "<text x=\"16\" y=\"" + Number((top + height - bottom) / 2) +
         "\" text-anchor=\"middle\" transform=\"rotate(-90 16 " + Number((top + height - bottom) / 2) + ")\">" +
         Escape(y_label) + "</text>\n";
  for (size_t k = 0; k < series.size(); ++k) {
    const char* color = kColors[k % 5];
    std::string points;
    auto flush = [&]() {
      if (!points.empty()) {
        svg += "<polyline fill=\"none\" stroke=\"" + std::string(color) + "\" stroke-width=\"1.2\" points=\"" +
               points + "\"/>\n";
      }
      points.clear();
    };
    for (size_t i = 0; i < series[k].y.size(); ++i) {
      const double v = series[k].y[i];
      if (!std::isfinite(v)) {
        flush();
        continue;
      }
      points += Number(px(static_cast<double>(i))) + "," + Number(py(v)) + " ";
    }
    flush();
    svg += "<text x=\"" + Number(width - right - 4) + "\" y=\"" + Number(top + 14 * (k + 1)) +
           "\" text-anchor=\"end\" fill=\"" + color + "\">" + Escape(series[k].name) + "</text>\n";
  }
  return svg + "</svg>\n";
}

}  // namespace mocapsolve
