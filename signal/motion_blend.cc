#include "signal/motion_blend.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "signal/motion_pyramid.h"

namespace mocapsolve {
namespace {

double Ease(double u) { return 0.5 * (1.0 - std::cos(kPi * std::clamp(u, 0.0, 1.0))); }

// `motion` placed at `offset` on a timeline of `frames`, end poses held outside it.
Motion PlaceOnTimeline(const Motion& motion, int offset, int frames) {
  Motion placed;
  placed.frame_rate = motion.frame_rate;
  placed.frames.reserve(frames);
  for (int t = 0; t < frames; ++t) {
    const int f = std::clamp(t - offset, 0, motion.num_frames() - 1);
    placed.frames.push_back(motion.frames[f]);
  }
  return placed;
}

void BlendRows(const Signal& a, const Signal& b, const std::vector<double>& weight_b, int stride,
               Signal* out) {
  out->resize(a.rows(), a.cols());
  for (int i = 0; i < a.rows(); ++i) {
    const int t = std::min(static_cast<int>(weight_b.size()) - 1, i * stride);
    const double w = weight_b[t];
    out->row(i) = (1.0 - w) * a.row(i) + w * b.row(i);
  }
}

}  // namespace

std::vector<double> BlendWeights(int frames_a, int frames_b, const BlendOptions& options) {
  const int s = options.transition_start, e = options.transition_end;
  const int b_last = options.b_offset + frames_b - 1;
  const int frames = std::max(frames_a, b_last + 1);
  const bool inside = b_last < frames_a - 1;
  std::vector<double> weights(frames, 0.0);
  for (int t = 0; t < frames; ++t) {
    if (t > b_last || t < s) continue;
    double w = Ease(static_cast<double>(t - s) / (e - s));
    if (inside) w = std::min(w, Ease(static_cast<double>(b_last - t) / (e - s)));
    weights[t] = w;
  }
  return weights;
}

Status BlendMotions(const Motion& a, const Motion& b, const BlendOptions& options, Motion* out) {
  const int na = a.num_frames(), nb = b.num_frames();
  if (na == 0 || nb == 0) return Status::Error("blend: both motions need frames");
  if (a.frames[0].rotations.size() != b.frames[0].rotations.size()) {
    return Status::Error("blend: the motions have different joint counts (" +
                         std::to_string(a.frames[0].rotations.size()) + " and " +
                         std::to_string(b.frames[0].rotations.size()) + ")");
  }
  if (!(a.frame_rate > 0.0)) return Status::Error("blend: frame rate must be positive");
  const int s = options.transition_start, e = options.transition_end;
  if (options.b_offset < 0) return Status::Error("blend: B's offset must be >= 0");
  if (s < options.b_offset || e <= s) {
    return Status::Error("transition " + std::to_string(s) + ":" + std::to_string(e) +
                         ": need B's start <= start < end");
  }
  if (e >= na) {
    return Status::Error("transition end " + std::to_string(e) + " past the first motion's " +
                         std::to_string(na) + " frames");
  }
  if (e >= options.b_offset + nb) {
    return Status::Error("transition end " + std::to_string(e) +
                         " past the second motion's end (frame " +
                         std::to_string(options.b_offset + nb - 1) + " of the result)");
  }
  const std::vector<double> weight_b = BlendWeights(na, nb, options);
  const int frames = static_cast<int>(weight_b.size());
  const Motion placed_a = PlaceOnTimeline(a, 0, frames);
  const Motion placed_b = PlaceOnTimeline(b, options.b_offset, frames);
  const QuaternionVector reference = ReferenceRotations(placed_a, s);
  Signal signal_a, signal_b, blended;
  MotionToSignal(placed_a, reference, s, &signal_a);
  MotionToSignal(placed_b, reference, s, &signal_b);

  if (options.method == BlendMethod::kWeightedSum) {
    BlendRows(signal_a, signal_b, weight_b, 1, &blended);
  } else {
    LaplacianPyramid pyramid_a, pyramid_b, pyramid;
    Status status = BuildLaplacianPyramid(signal_a, options.pyramid, &pyramid_a);
    if (!status.ok()) return status;
    status = BuildLaplacianPyramid(signal_b, options.pyramid, &pyramid_b);
    if (!status.ok()) return status;
    if (pyramid_a.levels() == 0) return Status::Error("blend: the clip is too short for a pyramid");
    pyramid.options = pyramid_a.options;
    const int levels = pyramid_a.levels();
    pyramid.laplacian.resize(levels);
    pyramid.gaussian.resize(levels);
    for (int l = 0; l < levels; ++l) {
      BlendRows(pyramid_a.laplacian[l], pyramid_b.laplacian[l], weight_b, 1 << l,
                &pyramid.laplacian[l]);
    }
    // Only the top Gaussian enters the collapse.
    BlendRows(pyramid_a.top(), pyramid_b.top(), weight_b, 1 << levels, &pyramid.gaussian.back());
    ReconstructSignal(pyramid, {}, &blended);
  }
  SignalToMotion(blended, placed_a, a.frame_rate, out);
  return Status::Ok();
}

std::vector<double> VelocityJumps(const Skeleton& skeleton, const Motion& motion) {
  const int frames = motion.num_frames();
  std::vector<double> jumps(std::max(frames, 0), 0.0);
  if (frames < 3) return jumps;
  FkData data(skeleton);
  std::vector<Vector3dVector> positions(frames);
  for (int f = 0; f < frames; ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &data);
    positions[f] = data.world_positions;
  }
  for (int f = 1; f + 1 < frames; ++f) {
    double jump = 0.0;
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      const Eigen::Vector3d change =
          positions[f + 1][j] - 2.0 * positions[f][j] + positions[f - 1][j];
      jump = std::max(jump, change.norm());
    }
    jumps[f] = jump;
  }
  return jumps;
}

}  // namespace mocapsolve
