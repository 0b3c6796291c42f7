#include "kinematics/frame_rate.h"

#include <cmath>

namespace mocapsolve {

double NominalFrameRate(double frame_rate) {
  const double rounded = std::round(frame_rate);
  return std::abs(frame_rate - rounded) <= 1e-5 * rounded ? rounded : frame_rate;
}

}  // namespace mocapsolve
