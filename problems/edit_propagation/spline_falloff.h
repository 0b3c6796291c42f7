// Spline falloff: the animator's usual tool, a smooth bump in time around the edited frame
// (the baseline the "magic wand" falloff replaces; Dean et al. 2018, Fig. 6).
//
//   w(f) = h(|f - i| / width),   h(s) = 1 - 3 s^2 + 2 s^3 for s < 1, 0 otherwise
//
// h is the cubic Hermite ease (value 1, slope 0 at s = 0; value 0, slope 0 at s = 1), so
// w is C1 in time, 1 at the edited frame i and 0 from `width` frames away on. Frames
// outside [region_begin, region_end) get 0. width > 0 (frames).
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_SPLINE_FALLOFF_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_SPLINE_FALLOFF_H_

#include <Eigen/Core>

namespace mocapsolve {

// region_end = -1: to the end of the clip.
Eigen::VectorXd SplineFalloff(int num_frames, int frame, double width, int region_begin = 0,
                              int region_end = -1);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_SPLINE_FALLOFF_H_
