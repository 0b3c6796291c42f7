#include "signal/motion_pyramid.h"

#include <cassert>
#include <cmath>

#include "kinematics/rotation.h"

namespace mocapsolve {
QuaternionVector ReferenceRotations(const Motion& motion, int frame) {
  return motion.frames[frame].rotations;
}

void MotionToSignal(const Motion& motion, const QuaternionVector& reference, int anchor_frame,
                    Signal* signal) {
  const int frames = motion.num_frames();
  const int joints = static_cast<int>(reference.size());
  assert(anchor_frame >= 0 && anchor_frame < frames);
  signal->resize(frames, 7 * joints);
  for (int f = 0; f < frames; ++f) {
    const Pose& pose = motion.frames[f];
    assert(static_cast<int>(pose.rotations.size()) == joints);
    for (int j = 0; j < joints; ++j) {
      const Eigen::Quaterniond& q = pose.rotations[j];
      signal->block<1, 4>(f, 4 * j) << q.w(), q.x(), q.y(), q.z();
      signal->block<1, 3>(f, 4 * joints + 3 * j) = pose.translations[j].transpose();
    }
  }
  for (int j = 0; j < joints; ++j) {
    auto column = signal->middleCols<4>(4 * j);
    for (int f = 1; f < frames; ++f) {
      if (column.row(f).dot(column.row(f - 1)) < 0.0) column.row(f) *= -1.0;
    }
    const Eigen::Quaterniond& r = reference[j];
    const Eigen::RowVector4d r_row(r.w(), r.x(), r.y(), r.z());
    if (column.row(anchor_frame).dot(r_row) < 0.0) column *= -1.0;
  }
}

void SignalToMotion(const Signal& signal, const Motion& fallback, double frame_rate,
                    Motion* motion) {
  const int joints = static_cast<int>(signal.cols() / 7);
  assert(signal.cols() == 7 * joints && fallback.num_frames() == signal.rows());
  motion->frame_rate = frame_rate;
  motion->frames.assign(signal.rows(), Pose());
  for (int f = 0; f < signal.rows(); ++f) {
    Pose& pose = motion->frames[f];
    pose.rotations.resize(joints);
    pose.translations.resize(joints);
    for (int j = 0; j < joints; ++j) {
      const Eigen::RowVector4d s = signal.block<1, 4>(f, 4 * j);
      const double norm = s.norm();
      pose.rotations[j] = norm > 1e-9 ? Eigen::Quaterniond(s[0] / norm, s[1] / norm, s[2] / norm,
                                                           s[3] / norm)
                                      : fallback.frames[f].rotations[j];
      pose.translations[j] = signal.block<1, 3>(f, 4 * joints + 3 * j).transpose();
    }
  }
  MakeSignContinuous(motion);
}

void MarkersToSignal(const MarkerTrajectories& trajectories, Signal* signal) {
  const int frames = trajectories.num_frames();
  const int markers = trajectories.num_markers();
  signal->setZero(frames, 3 * markers);
  for (int m = 0; m < markers; ++m) {
    int previous = -1;  // Last valid frame seen.
    for (int f = 0; f < frames; ++f) {
      if (!trajectories.valid(f, m)) continue;
      const Eigen::Vector3d p = trajectories.position(f, m);
      signal->block<1, 3>(f, 3 * m) = p.transpose();
      if (previous < 0) {
        for (int g = 0; g < f; ++g) signal->block<1, 3>(g, 3 * m) = p.transpose();
      } else {
        const Eigen::Vector3d q = trajectories.position(previous, m);
        for (int g = previous + 1; g < f; ++g) {
          const double t = static_cast<double>(g - previous) / (f - previous);
          signal->block<1, 3>(g, 3 * m) = ((1.0 - t) * q + t * p).transpose();
        }
      }
      previous = f;
    }
    if (previous >= 0) {
      const Eigen::Vector3d q = trajectories.position(previous, m);
      for (int g = previous + 1; g < frames; ++g) signal->block<1, 3>(g, 3 * m) = q.transpose();
    }
  }
}

Status FilterMotion(const Motion& motion, const PyramidOptions& options,
                    const std::vector<double>& weights, Motion* filtered) {
  if (motion.num_frames() == 0) return Status::Error("the motion has no frames");
  const QuaternionVector reference = ReferenceRotations(motion, 0);
  Signal signal;
  MotionToSignal(motion, reference, 0, &signal);
  LaplacianPyramid pyramid;
  Status status = BuildLaplacianPyramid(signal, options, &pyramid);
  if (!status.ok()) return status;
  if (pyramid.levels() == 0) return Status::Error("the motion is too short for a pyramid");
  if (!weights.empty()) {
    status = CheckBandWeights(weights, pyramid.levels(), "weights");
    if (!status.ok()) return status;
  }
  Signal out;
  ReconstructSignal(pyramid, weights, &out);
  SignalToMotion(out, motion, motion.frame_rate, filtered);
  return Status::Ok();
}

Status FilterMarkers(const MarkerTrajectories& trajectories, const PyramidOptions& options,
                     const std::vector<double>& weights, MarkerTrajectories* filtered) {
  if (trajectories.num_frames() == 0) return Status::Error("the trajectories have no frames");
  Signal signal;
  MarkersToSignal(trajectories, &signal);
  LaplacianPyramid pyramid;
  Status status = BuildLaplacianPyramid(signal, options, &pyramid);
  if (!status.ok()) return status;
  if (pyramid.levels() == 0) return Status::Error("the trajectories are too short for a pyramid");
  if (!weights.empty()) {
    status = CheckBandWeights(weights, pyramid.levels(), "weights");
    if (!status.ok()) return status;
  }
  Signal out;
  ReconstructSignal(pyramid, weights, &out);
  MarkerTrajectories result = trajectories;
  for (int f = 0; f < trajectories.num_frames(); ++f) {
    for (int m = 0; m < trajectories.num_markers(); ++m) {
      if (!trajectories.valid(f, m)) continue;  // Stays missing (masked back).
      result.SetSample(f, m, out.block<1, 3>(f, 3 * m).transpose(), trajectories.residual(f, m),
                       trajectories.camera_mask(f, m));
    }
  }
  *filtered = std::move(result);
  return Status::Ok();
}

}  // namespace mocapsolve
