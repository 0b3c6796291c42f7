#include "io/curve_key_reduction.h"

#include <algorithm>
#include <limits>

namespace mocapsolve {

CurveKeys ReduceLinearKeys(const std::vector<float>& samples, double tolerance) {
  const int n = static_cast<int>(samples.size());
  CurveKeys keys;
  if (n == 0) return keys;
  keys.frames.push_back(0);
  keys.values.push_back(samples[0]);
  int a = 0;
  double ya = samples[0];
  while (a < n - 1) {
    double low = -std::numeric_limits<double>::infinity();
    double high = std::numeric_limits<double>::infinity();
    int b = a;
    for (int i = a + 1; i < n; ++i) {
      const double span = i - a;
      const double new_low = std::max(low, (samples[i] - tolerance - ya) / span);
      const double new_high = std::min(high, (samples[i] + tolerance - ya) / span);
      if (new_low > new_high) break;
      low = new_low;
      high = new_high;
      b = i;
    }
    const double slope = 0.5 * (low + high);
    // Sample a + 1 always fits (its interval is not empty), so b > a. At tolerance 0 the
    // keys are the samples themselves (no rounding of the line's end).
    const double yb = tolerance == 0.0 ? samples[b] : ya + slope * (b - a);
    keys.frames.push_back(b);
    keys.values.push_back(static_cast<float>(yb));
    a = b;
    ya = static_cast<float>(yb);
  }
  return keys;
}

}  // namespace mocapsolve
