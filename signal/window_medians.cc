#include "signal/window_medians.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace mocapsolve {

std::vector<double> WindowMedians(const std::vector<double>& values, const std::vector<char>& valid,
                                  const std::vector<int>& knots, int half, double fallback) {
  assert(values.size() == valid.size() && half >= 0);
  const int nf = static_cast<int>(values.size());
  std::vector<double> medians(knots.size(), fallback);
  bool finite = true;
  for (int f = 0; f < nf && finite; ++f) finite = !valid[f] || std::isfinite(values[f]);
  if (!finite) {
    std::vector<double> window;
    for (size_t i = 0; i < knots.size(); ++i) {
      window.clear();
      for (int g = std::max(0, knots[i] - half); g <= std::min(nf - 1, knots[i] + half); ++g) {
        if (valid[g]) window.push_back(values[g]);
      }
      if (window.empty()) continue;
      std::nth_element(window.begin(), window.begin() + window.size() / 2, window.end());
      medians[i] = window[window.size() / 2];
    }
    return medians;
  }
  std::vector<double> sorted;
  int lo = 0, hi = -1;  // Frames lo..hi are in `sorted`.
  for (size_t i = 0; i < knots.size(); ++i) {
    assert(i == 0 || knots[i] >= knots[i - 1]);
    const int a = std::max(0, knots[i] - half), b = std::min(nf - 1, knots[i] + half);
    for (; hi < b; ++hi) {
      if (valid[hi + 1]) sorted.insert(std::upper_bound(sorted.begin(), sorted.end(), values[hi + 1]), values[hi + 1]);
    }
    for (; lo < a; ++lo) {
      if (valid[lo]) sorted.erase(std::lower_bound(sorted.begin(), sorted.end(), values[lo]));
    }
    if (!sorted.empty()) medians[i] = sorted[sorted.size() / 2];
  }
  return medians;
}

}  // namespace mocapsolve
