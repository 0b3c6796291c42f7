// A clip as it is delivered to an engine or a DCC tool: cut to a range of its frames, then
// resampled to another frame rate (the delivery options of settings/delivery_settings.h:
// --frames=A:B, --seconds=A:B, --out_fps).
//
// Range: frames first..last of the clip, both included, 0-based; by seconds, the frames
// whose times k / frame_rate lie in [A, B] (to 1e-9 s). A range must hold at least one
// frame and lie inside the clip; an error names the option as given ("--frames=10:500:
// the clip has 300 frames, 0:299").
//
// Resampling to rate r: frame k of the result is the cut clip at time k / r, k = 0 ..
// floor(duration * r + 1e-6), so the result never extrapolates past the last frame. Between
// the two frames i, i + 1 around time t (s = t * frame_rate, a = s - i): translations
// linearly, (1 - a) t_i + a t_i+1; rotations by spherical linear interpolation between q_i
// and whichever of +-q_i+1 is nearer to it (sign-continuous: never the long way round), so
// a rate equal to the clip's gives its frames back exactly. 0 keeps the rate.
#ifndef MOCAPSOLVE_SIGNAL_CLIP_DELIVERY_H_
#define MOCAPSOLVE_SIGNAL_CLIP_DELIVERY_H_

#include <string>

#include "kinematics/motion.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct ClipRange {
  enum class Unit { kAll, kFrames, kSeconds };
  Unit unit = Unit::kAll;
  bool has_first = false, has_last = false;  // "A:" or ":B" leave one end open.
  double first = 0.0, last = 0.0;            // Frames (whole numbers) or seconds.
  std::string option;                        // As given, for messages: "--frames=10:500".
};

struct ClipDelivery {
  ClipRange range;
  double out_fps = 0.0;  // 0 = the clip's rate.
  // The FBX writer's key reduction bound (io/fbx_writer.h, FbxWriteOptions), mm; 0 = exact.
  double fbx_key_tolerance_mm = 0.0;

  bool keeps_clip() const { return range.unit == ClipRange::Unit::kAll && out_fps == 0.0; }
};

// The frames the range keeps of a clip of `frames` frames at `frame_rate`: first..last,
// both included; an error naming the option when the range lies outside the clip or holds
// no frame.
Status ResolveClipRange(const ClipRange& range, int frames, double frame_rate, int* first, int* last);

// `motion` resampled to `frame_rate` as described above (a positive rate; a clip of one
// frame stays one frame; more than 10^7 frames is an error).
Status ResampleMotion(const Motion& motion, double frame_rate, Motion* resampled);

// `clip` cut to the delivery's range, then resampled to its out_fps. `out` may be `&clip`.
Status DeliverClip(const Motion& clip, const ClipDelivery& delivery, Motion* out);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_CLIP_DELIVERY_H_
