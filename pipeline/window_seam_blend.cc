#include "pipeline/window_seam_blend.h"

#include <algorithm>

#include "signal/motion_blend.h"

namespace mocapsolve {
namespace {

// Frames [first, first + count) of `motion`.
Motion Frames(const Motion& motion, int first, int count) {
  Motion part;
  part.frame_rate = motion.frame_rate;
  part.frames.assign(motion.frames.begin() + first, motion.frames.begin() + first + count);
  return part;
}

// Where both windows give a joint the same value (a bone's fixed offset, a joint no solve
// moves), the joined frame keeps it exactly, not to rounding: the BVH writer and the compact
// take tell a moving channel by exact change.
void KeepWhatAgrees(const Motion& a, const Motion& b, Motion* joined) {
  for (int f = 0; f < joined->num_frames(); ++f) {
    const Pose &pa = a.frames[f], &pb = b.frames[f];
    Pose& out = joined->frames[f];
    for (size_t j = 0; j < out.rotations.size(); ++j) {
      if (pa.translations[j] == pb.translations[j]) out.translations[j] = pa.translations[j];
      if (pa.rotations[j].coeffs() == pb.rotations[j].coeffs()) out.rotations[j] = pa.rotations[j];
    }
  }
}

}  // namespace

Status WindowSeamBlend::Add(const Motion& motion, const FrameWindow& w, bool last, const Emit& emit) {
  const Emit emit_some = [&emit](const Motion& m, int first, int count) {
    return count > 0 ? emit(m, first, count) : Status::Ok();
  };
  int from = w.core_first;  // The take's first frame of this window still to emit.
  if (!tail_.frames.empty()) {
    const int held = seam_ - tail_first_;
    const int b = std::min({blend_frames_, held, tail_.num_frames() - held, seam_ - w.first, w.core_last + 1 - seam_});
    Status status = emit_some(tail_, 0, held - b);  // Held back, not blended.
    if (status.ok() && b > 0) {
      BlendOptions blend;
      blend.method = BlendMethod::kWeightedSum;
      blend.transition_end = 2 * b - 1;
      const Motion a = Frames(tail_, held - b, 2 * b), next = Frames(motion, seam_ - b - w.first, 2 * b);
      Motion joined;
      status = BlendMotions(a, next, blend, &joined);
      if (status.ok()) {
        KeepWhatAgrees(a, next, &joined);
        status = emit_some(joined, 0, 2 * b);
      }
      from = seam_ + b;
    }
    tail_ = Motion();
    if (!status.ok()) return status;
  }
  const int end = w.core_last + 1;
  const int hold = last ? 0 : std::max(0, std::min(blend_frames_, end - from));
  Status status = emit_some(motion, from - w.first, end - hold - from);
  if (!status.ok() || last) return status;
  tail_first_ = end - hold;
  seam_ = end;
  const int kept_after = std::min(w.last + 1, end + blend_frames_) - tail_first_;
  tail_ = Frames(motion, tail_first_ - w.first, kept_after);
  return Status::Ok();
}

}  // namespace mocapsolve
