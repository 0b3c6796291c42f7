#include "problems/retarget/root_motion.h"

#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "kinematics/forward_kinematics.h"

namespace mocapsolve {
namespace {

// Gaussian smoothing (standard deviation `sigma` samples, truncated at 3 sigma) with the
// series point-reflected about its end samples, so a linear series stays linear.
std::vector<double> Smooth(const std::vector<double>& x, double sigma) {
  const int n = static_cast<int>(x.size());
  if (n < 2 || !(sigma > 0.0)) return x;
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  auto at = [&](int i) {
    if (i < 0) return 2.0 * x[0] - x[std::min(-i, n - 1)];
    if (i >= n) return 2.0 * x[n - 1] - x[std::max(2 * (n - 1) - i, 0)];
    return x[i];
  };
  std::vector<double> out(n);
  for (int i = 0; i < n; ++i) {
    double sum = 0.0, weight = 0.0;
    for (int k = -radius; k <= radius; ++k) {
      const double w = std::exp(-0.5 * k * k / (sigma * sigma));
      sum += w * at(i + k);
      weight += w;
    }
    out[i] = sum / weight;
  }
  return out;
}

// Sets the root's world position and rotation to (position, rotation) in `pose`, every
// child of the root keeping its world frame (root_motion.h).
void SetRootKeepingChildren(const Skeleton& skeleton, const Eigen::Vector3d& position,
                            const Eigen::Quaterniond& rotation, Pose* pose) {
  const Eigen::Quaterniond rest = skeleton.rest_rotation(0);
  const Eigen::Vector3d old_position = pose->translations[0];
  const Eigen::Quaterniond old_rotation = rest * pose->rotations[0];
  const Eigen::Quaterniond inverse = rotation.conjugate();
  for (int c = 1; c < skeleton.num_joints(); ++c) {
    if (skeleton.parent(c) != 0) continue;
    pose->translations[c] = inverse * (old_position + old_rotation * pose->translations[c] - position);
    const Eigen::Quaterniond rest_c = skeleton.rest_rotation(c);
    pose->rotations[c] = (rest_c.conjugate() * inverse * old_rotation * rest_c * pose->rotations[c]).normalized();
  }
  pose->translations[0] = position;
  pose->rotations[0] = (rest.conjugate() * rotation).normalized();
}

}  // namespace

bool ParseRootMotionMode(const std::string& text, RootMotionMode* mode) {
  if (text == "keep") return *mode = RootMotionMode::kKeep, true;
  if (text == "root_bone") return *mode = RootMotionMode::kRootBone, true;
  if (text == "in_place") return *mode = RootMotionMode::kInPlace, true;
  return false;
}

const char* RootMotionModeName(RootMotionMode mode) {
  switch (mode) {
    case RootMotionMode::kRootBone:
      return "root_bone";
    case RootMotionMode::kInPlace:
      return "in_place";
    default:
      return "keep";
  }
}

int FirstBranchingJoint(const Skeleton& skeleton) {
  const int n = skeleton.num_joints();
  std::vector<int> children_count(n, 0);
  for (int c = 1; c < n; ++c) ++children_count[skeleton.parent(c)];
  int joint = 0;
  while (true) {
    std::vector<int> chains;  // Children that have children of their own.
    for (int c = joint + 1; c < n; ++c) {
      if (skeleton.parent(c) == joint && children_count[c] > 0) chains.push_back(c);
    }
    if (chains.size() != 1) return joint;
    joint = chains[0];
  }
}

void MeasureRootTrack(const Skeleton& skeleton, int hips, const Motion& motion, double smoothing_seconds,
                      RootMotionResult* result) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, RestPose(skeleton), &fk);
  const Eigen::Quaterniond rest_inverse = fk.world_rotations[hips].conjugate();
  const int n = motion.num_frames();
  std::vector<double> x(n), z(n), heading(n);
  for (int f = 0; f < n; ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    x[f] = fk.world_positions[hips].x();
    z[f] = fk.world_positions[hips].z();
    const Eigen::Quaterniond relative = fk.world_rotations[hips] * rest_inverse;
    double h = 2.0 * std::atan2(relative.y(), relative.w());
    if (f > 0) h += 2.0 * M_PI * std::round((heading[f - 1] - h) / (2.0 * M_PI));  // Unwrapped.
    heading[f] = h;
  }
  const double sigma = motion.frame_rate > 0.0 ? smoothing_seconds * motion.frame_rate : 0.0;
  x = Smooth(x, sigma);
  z = Smooth(z, sigma);
  result->heading = Smooth(heading, sigma);
  result->hips = hips;
  result->track.assign(n, Eigen::Vector3d::Zero());
  result->track_length = 0.0;
  for (int f = 0; f < n; ++f) {
    result->track[f] = Eigen::Vector3d(x[f], 0.0, z[f]);
    if (f > 0) result->track_length += (result->track[f] - result->track[f - 1]).norm();
  }
}

Status ApplyRootMotion(const Skeleton& skeleton, int hips, const RootMotionOptions& options, Motion* motion,
                       RootMotionResult* result) {
  *result = RootMotionResult();
  result->hips = hips;
  if (options.mode == RootMotionMode::kKeep || motion->num_frames() == 0) return Status::Ok();
  if (hips < 0 || hips >= skeleton.num_joints()) return Status::Error("root motion: no hips joint");
  if (options.mode == RootMotionMode::kRootBone && hips == 0) {
    return Status::Error("--root_motion=root_bone: the target has no root bone above its hips ('" + skeleton.name(0) +
                         "' is the skeleton's root); use keep or in_place");
  }
  if (options.smoothing_seconds > 0.0 && !(motion->frame_rate > 0.0)) {
    return Status::Error("root motion: the clip has no frame rate to smooth the track over");
  }
  MeasureRootTrack(skeleton, hips, *motion, options.smoothing_seconds, result);
  const Eigen::Vector3d rest_position = skeleton.offset(0);
  const Eigen::Quaterniond rest_rotation = skeleton.rest_rotation(0);
  for (int f = 0; f < motion->num_frames(); ++f) {
    Pose& pose = motion->frames[f];
    if (options.mode == RootMotionMode::kRootBone) {
      const Eigen::Vector3d position(result->track[f].x(), rest_position.y(), result->track[f].z());
      const Eigen::Quaterniond turn(Eigen::AngleAxisd(result->heading[f], Eigen::Vector3d::UnitY()));
      SetRootKeepingChildren(skeleton, position, turn * rest_rotation, &pose);
      continue;
    }
    pose.translations[0] -= result->track[f] - result->track[0];  // The root's parent frame is the world.
    if (hips != 0) SetRootKeepingChildren(skeleton, rest_position, rest_rotation, &pose);
  }
  if (hips != 0) result->root_bone = 0;
  char buffer[400];
  std::snprintf(buffer, sizeof buffer,
                "root motion %s: the track of '%s' (ground projection and heading, smoothed over %.2f s) is "
                "%.3g units long, heading %.0f to %.0f deg%s",
                RootMotionModeName(options.mode), skeleton.name(hips).c_str(), options.smoothing_seconds,
                result->track_length, result->heading.front() * 180.0 / M_PI, result->heading.back() * 180.0 / M_PI,
                options.mode == RootMotionMode::kRootBone
                    ? ("; carried by the root bone '" + skeleton.name(0) + "'").c_str()
                    : (hips != 0 ? ("; removed, the root bone '" + skeleton.name(0) + "' kept at rest").c_str()
                                 : "; removed from the hips"));
  result->note = buffer;
  return Status::Ok();
}

}  // namespace mocapsolve
