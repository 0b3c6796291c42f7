#include "signal/clip_delivery.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mocapsolve {
namespace {

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

}  // namespace

Status ResolveClipRange(const ClipRange& range, int frames, double frame_rate, int* first, int* last) {
  if (frames < 1) return Status::Error(range.option + ": the clip has no frames");
  *first = 0;
  *last = frames - 1;
  switch (range.unit) {
    case ClipRange::Unit::kAll:
      return Status::Ok();
    case ClipRange::Unit::kFrames: {
      if (range.has_first) *first = static_cast<int>(std::min<double>(range.first, frames));
      if (range.has_last) *last = static_cast<int>(std::min<double>(range.last, frames));
      if ((range.has_first && range.first > frames - 1) || (range.has_last && range.last > frames - 1)) {
        return Status::Error(range.option + ": the clip has " + std::to_string(frames) + " frames, 0:" +
                             std::to_string(frames - 1));
      }
      break;
    }
    case ClipRange::Unit::kSeconds: {
      if (!(frame_rate > 0.0)) return Status::Error(range.option + ": the clip has no frame rate");
      const double duration = (frames - 1) / frame_rate;
      constexpr double kSlack = 1e-9;  // Seconds: a bound given as a frame's time keeps it.
      if ((range.has_first && range.first > duration + kSlack) || (range.has_last && range.last > duration + kSlack)) {
        return Status::Error(range.option + ": the clip lasts " + Number(duration) + " s, 0:" + Number(duration));
      }
      if (range.has_first) *first = static_cast<int>(std::ceil((range.first - kSlack) * frame_rate));
      if (range.has_last) *last = static_cast<int>(std::floor((range.last + kSlack) * frame_rate));
      *first = std::clamp(*first, 0, frames - 1);
      *last = std::clamp(*last, 0, frames - 1);
      break;
    }
  }
  if (*first > *last) return Status::Error(range.option + ": holds no frame (the first is after the last)");
  return Status::Ok();
}

Status ResampleMotion(const Motion& motion, double frame_rate, Motion* resampled) {
  if (!(frame_rate > 0.0) || !std::isfinite(frame_rate)) {
    return Status::Error("resample: the rate must be positive, got " + Number(frame_rate));
  }
  if (!(motion.frame_rate > 0.0)) return Status::Error("resample: the clip has no frame rate");
  if (motion.frames.empty()) return Status::Error("resample: the clip has no frames");
  const int frames = motion.num_frames();
  const double last = std::floor((frames - 1) / motion.frame_rate * frame_rate + 1e-6);
  constexpr double kMaxFrames = 1e7;  // Hours of a clip at any engine's rate.
  if (!(last < kMaxFrames)) {
    return Status::Error("resample: " + Number(frame_rate) + " fps would make more than 10^7 frames of a " +
                         Number((frames - 1) / motion.frame_rate) + " s clip");
  }
  const int count = static_cast<int>(last) + 1;
  Motion out;
  out.frame_rate = frame_rate;
  out.frames.resize(count);
  for (int k = 0; k < count; ++k) {
    const double s = k * motion.frame_rate / frame_rate;
    const int i = std::min(static_cast<int>(std::floor(s)), std::max(frames - 2, 0));
    const double a = frames == 1 ? 0.0 : std::clamp(s - i, 0.0, 1.0);
    const Pose& p0 = motion.frames[i];
    const Pose& p1 = motion.frames[std::min(i + 1, frames - 1)];
    Pose& pose = out.frames[k];
    if (a == 0.0) {
      pose = p0;
      continue;
    }
    if (a == 1.0) {
      pose = p1;
      continue;
    }
    const size_t joints = p0.rotations.size();
    pose.translations.resize(joints);
    pose.rotations.resize(joints);
    for (size_t j = 0; j < joints; ++j) {
      pose.translations[j] = (1.0 - a) * p0.translations[j] + a * p1.translations[j];
      Eigen::Quaterniond q1 = p1.rotations[j];
      if (p0.rotations[j].dot(q1) < 0.0) q1.coeffs() = -q1.coeffs();
      pose.rotations[j] = p0.rotations[j].slerp(a, q1).normalized();
    }
  }
  *resampled = std::move(out);
  return Status::Ok();
}

Status DeliverClip(const Motion& clip, const ClipDelivery& delivery, Motion* out) {
  int first = 0, last = 0;
  Status status = ResolveClipRange(delivery.range, clip.num_frames(), clip.frame_rate, &first, &last);
  if (!status.ok()) return status;
  Motion cut;
  cut.frame_rate = clip.frame_rate;
  cut.frames.assign(clip.frames.begin() + first, clip.frames.begin() + last + 1);
  if (delivery.out_fps == 0.0) {
    *out = std::move(cut);
    return Status::Ok();
  }
  status = ResampleMotion(cut, delivery.out_fps, out);
  return status.ok() ? status : Status::Error("--out_fps: " + status.message());
}

}  // namespace mocapsolve
