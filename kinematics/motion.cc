#include "kinematics/motion.h"

#include <cmath>

#include "kinematics/rotation.h"

namespace mocapsolve {

Pose RestPose(const Skeleton& skeleton) {
  Pose pose;
  pose.translations.resize(skeleton.num_joints());
  pose.rotations.assign(skeleton.num_joints(), Eigen::Quaterniond::Identity());
  for (int j = 0; j < skeleton.num_joints(); ++j) pose.translations[j] = skeleton.offset(j);
  return pose;
}

void MakeSignContinuous(Motion* motion) {
  for (size_t f = 1; f < motion->frames.size(); ++f) {
    QuaternionVector& now = motion->frames[f].rotations;
    const QuaternionVector& before = motion->frames[f - 1].rotations;
    for (size_t j = 0; j < now.size(); ++j) {
      if (now[j].dot(before[j]) < 0.0) now[j].coeffs() = -now[j].coeffs();
    }
  }
}

Status ValidateMotion(const Skeleton& skeleton, const Motion& motion) {
  if (!(motion.frame_rate > 0.0) || !std::isfinite(motion.frame_rate)) {
    return Status::Error("frame rate must be positive");
  }
  for (int f = 0; f < motion.num_frames(); ++f) {
    Status status = ValidatePose(skeleton, motion.frames[f], "frame " + std::to_string(f));
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

Status ValidatePose(const Skeleton& skeleton, const Pose& pose, const std::string& where) {
  const size_t nj = skeleton.num_joints();
  if (pose.translations.size() != nj || pose.rotations.size() != nj) {
    return Status::Error(where + ": pose has the wrong joint count (" + std::to_string(pose.rotations.size()) +
                         ", skeleton " + std::to_string(nj) + ")");
  }
  for (size_t j = 0; j < nj; ++j) {
    if (!pose.translations[j].allFinite() || !pose.rotations[j].coeffs().allFinite() ||
        std::abs(pose.rotations[j].norm() - 1.0) > 1e-6) {
      return Status::Error(where + ", joint '" + skeleton.name(j) + "': non-finite value or non-unit rotation");
    }
  }
  return Status::Ok();
}

}  // namespace mocapsolve
