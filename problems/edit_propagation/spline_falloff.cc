#include "problems/edit_propagation/spline_falloff.h"

#include <algorithm>
#include <cmath>

#include <glog/logging.h>

namespace mocapsolve {

Eigen::VectorXd SplineFalloff(int num_frames, int frame, double width, int region_begin,
                              int region_end) {
  CHECK_GT(width, 0.0);
  if (region_end < 0) region_end = num_frames;
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(num_frames);
  for (int f = std::max(0, region_begin); f < std::min(num_frames, region_end); ++f) {
    const double s = std::abs(f - frame) / width;
    if (s < 1.0) weights[f] = 1.0 - s * s * (3.0 - 2.0 * s);
  }
  return weights;
}

}  // namespace mocapsolve
