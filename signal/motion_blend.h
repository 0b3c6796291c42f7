// Blending two motions of one skeleton: the plain weighted sum (Huang, Boulic & Thalmann,
// eq. 6) and the multiresolution blend of their section 3 (Burt & Adelson's mosaic).
//
// Timeline: frames of motion A; B's frame 0 lies at A's frame b_offset (>= 0). The result
// has max(#A, b_offset + #B) frames. B's weight w_B(t) (A's is 1 - w_B):
//   0 before transition_start, ease((t - s) / (e - s)) over [s, e] = [transition_start,
//   transition_end], 1 after it; ease(u) = (1 - cos(pi u)) / 2, the ease-in/ease-out
//   weight of eq. 6 (zero slope at both ends).
// The second motion inside the first (b_offset + #B < #A, the paper's t3 > t1, t4 < t2):
//   B also eases out over its last (e - s) frames, w_B = min(ease in, ease out), and A
//   takes over again; when B is shorter than two windows the two ramps meet and w_B peaks
//   below 1 at B's middle (the paper's weight reaching 0 at (t3 + t4) / 2 for A).
// Outside a motion's own frames (A after its end, B before its start or after its end)
// it is extended by holding its end pose; the weight there is 0, but the pyramid's
// coarse bands see the extension.
//
// Both methods blend the same channels (motion_pyramid.h: sign-continuous quaternions,
// B's series given the sign nearer A's at transition_start, renormalized after the blend;
// translations per channel):
//   kWeightedSum:      S(t) = (1 - w_B(t)) S_A(t) + w_B(t) S_B(t)                     (eq. 6)
//   kMultiresolution:  L_{3,l}(i) = (1 - w_B(2^l i)) L_{A,l}(i) + w_B(2^l i) L_{B,l}(i)
//                      for every band and the top Gaussian, then collapse (eq. 4).
// At level l the weight steps between nodes 2^l frames apart and the collapse smooths
// each band's seam over its own wavelength, which is what makes the seam invisible.
// Blending a motion with itself (b_offset = 0) returns it (to rounding) with either method.
#ifndef MOCAPSOLVE_SIGNAL_MOTION_BLEND_H_
#define MOCAPSOLVE_SIGNAL_MOTION_BLEND_H_

#include <vector>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "signal/laplacian_pyramid.h"

namespace mocapsolve {

enum class BlendMethod { kMultiresolution, kWeightedSum };

struct BlendOptions {
  int b_offset = 0;          // A's frame at which B's frame 0 lies.
  int transition_start = 0;  // s, in A's frames; b_offset <= s.
  int transition_end = 0;    // e > s; A and B must both cover [s, e].
  BlendMethod method = BlendMethod::kMultiresolution;
  PyramidOptions pyramid;    // levels 0 = as many as the blended clip allows.
};

// w_B at each frame of the result (see above). Options assumed valid.
std::vector<double> BlendWeights(int frames_a, int frames_b, const BlendOptions& options);

// Fails (one line naming the option) on a bad window, different joint counts or a
// non-positive frame rate; the result's frame rate is A's.
Status BlendMotions(const Motion& a, const Motion& b, const BlendOptions& options, Motion* out);

// Per frame f in [1, #F - 2], the largest over joints of |p(f+1) - 2 p(f) + p(f-1)|: the
// jump of every joint's world velocity (per frame) between consecutive frames, in the
// skeleton's units. Entries 0 and #F - 1 are 0.
std::vector<double> VelocityJumps(const Skeleton& skeleton, const Motion& motion);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_MOTION_BLEND_H_
