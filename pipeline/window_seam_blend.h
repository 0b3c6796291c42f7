// WindowSeamBlend: a windowed take's motion (the solve, a character's retarget) joined
// window by window with a cross-fade at each seam, so that where one window's solve hands
// over to the next there is no pop. Each window solves its core and some context on each
// side (pipeline/take_windows.h) on its own: a joint the markers leave free (a thumb),
// the retarget's per-window set-up and its foot contacts can differ between two windows by
// centimetres over the frames both solve, and joining the cores edge to edge shows that
// difference as a jump in one frame (measured in BENCHMARKS.md: 3-10 cm at the toes and
// fingers, against 1-3 cm between any two frames).
//
// At the seam s between windows A and B (s = B's first core frame), with
// b = min(blend_frames, frames of A held back before s, frames A solved after s, frames B
// solved before s), frames [s - b, s + b) are the weighted sum of A's and B's
// (signal/motion_blend.h, kWeightedSum: sign-continuous quaternions and translations,
// B's weight easing from 0 to 1, zero slope at both ends); every other frame is its own
// window's, untouched. With blend_frames = 0 the cores are joined edge to edge.
#ifndef MOCAPSOLVE_PIPELINE_WINDOW_SEAM_BLEND_H_
#define MOCAPSOLVE_PIPELINE_WINDOW_SEAM_BLEND_H_

#include <functional>

#include "kinematics/motion.h"
#include "kinematics/status.h"
#include "pipeline/take_windows.h"

namespace mocapsolve {

class WindowSeamBlend {
 public:
  // Takes frames [first, first + count) of a motion, in the take's order.
  using Emit = std::function<Status(const Motion& motion, int first, int count)>;

  explicit WindowSeamBlend(int blend_frames) : blend_frames_(blend_frames) {}

  // The motion of one window, frames [w.first, w.last] of the take (w.core_* its core),
  // given in window order; emits every frame it can settle: the previous window's held-back
  // frames, the seam's blend and this window's core but the last blend_frames (held back
  // for the next seam), or all of its core when `last`.
  Status Add(const Motion& motion, const FrameWindow& w, bool last, const Emit& emit);

 private:
  int blend_frames_;
  Motion tail_;         // The previous window's frames from the first held back.
  int tail_first_ = 0;  // The take's frame of tail_.frames[0].
  int seam_ = 0;        // The take's frame after the previous window's core.
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_WINDOW_SEAM_BLEND_H_
