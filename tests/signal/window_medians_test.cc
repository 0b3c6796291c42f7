// Sliding-window medians: the sorted window carried from knot to knot gives, at every knot,
// the median a fresh selection over that window gives (ties, gaps, empty windows, the
// signal's ends, knots closer and farther apart than the window).
#include "signal/window_medians.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// The median of each window selected afresh.
std::vector<double> Fresh(const std::vector<double>& values, const std::vector<char>& valid,
                          const std::vector<int>& knots, int half, double fallback) {
  const int nf = static_cast<int>(values.size());
  std::vector<double> out;
  for (int f : knots) {
    std::vector<double> window;
    for (int g = std::max(0, f - half); g <= std::min(nf - 1, f + half); ++g) {
      if (valid[g]) window.push_back(values[g]);
    }
    std::sort(window.begin(), window.end());
    out.push_back(window.empty() ? fallback : window[window.size() / 2]);
  }
  return out;
}

TEST(WindowMedians, EqualFreshSelectionAtEveryKnot) {
  uint64_t state = 7;
  const auto next = [&state]() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return state >> 33;
  };
  int checked = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int nf = 1 + static_cast<int>(next() % 300);
    const int half = static_cast<int>(next() % 40);
    const int stride = 1 + static_cast<int>(next() % 20);
    std::vector<double> values(nf);
    std::vector<char> valid(nf);
    const int gap_rate = static_cast<int>(next() % 4);  // 0: none missing; 3: most.
    for (int f = 0; f < nf; ++f) {
      values[f] = trial % 3 == 0 ? static_cast<double>(next() % 5)  // Many ties.
                                 : std::sin(0.1 * f) + 1e-3 * static_cast<double>(next() % 1000);
      valid[f] = static_cast<int>(next() % 4) >= gap_rate;
      if (f > nf / 3 && f < nf / 3 + 50 && trial % 5 == 0) valid[f] = 0;  // A long gap: empty windows.
    }
    std::vector<int> knots;
    for (int f = 0; f < nf; f += stride) knots.push_back(f);
    if (knots.back() != nf - 1) knots.push_back(nf - 1);
    const std::vector<double> expected = Fresh(values, valid, knots, half, -7.0);
    EXPECT_EQ(WindowMedians(values, valid, knots, half, -7.0), expected) << "trial " << trial;
    checked += static_cast<int>(knots.size());
  }
  EXPECT_GT(checked, 1000);
}

TEST(WindowMedians, ANonFiniteValueIsSelectedAfresh) {
  std::vector<double> values = {3, 1, std::numeric_limits<double>::quiet_NaN(), 2, 5, 4, 0};
  const std::vector<char> valid = {1, 1, 0, 1, 1, 1, 1};
  // Invalid: ignored, the sorted path runs.
  EXPECT_EQ(WindowMedians(values, valid, {0, 3, 6}, 2, -1.0), (std::vector<double>{3, 4, 4}));
  // Valid and not finite: the windows without it still get their medians.
  const std::vector<char> all(7, 1);
  const std::vector<double> medians = WindowMedians(values, all, {0, 6}, 1, -1.0);
  EXPECT_EQ(medians[0], 3.0);
  EXPECT_EQ(medians[1], 4.0);
}

}  // namespace
}  // namespace mocapsolve
