#include "problems/marker_solve/mean_pose.h"

namespace mocapsolve {

Eigen::Quaterniond MeanLocalRotation(const Motion& motion, int joint) {
  if (motion.frames.empty()) return Eigen::Quaterniond::Identity();
  const Eigen::Vector4d first = motion.frames[0].rotations[joint].coeffs();
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  for (const Pose& pose : motion.frames) {
    const Eigen::Vector4d q = pose.rotations[joint].coeffs();
    sum += (q.dot(first) < 0.0 ? -1.0 : 1.0) * q;
  }
  Eigen::Quaterniond mean;
  mean.coeffs() = sum.normalized();
  return mean;
}

QuaternionVector MeanPose(const Skeleton& skeleton, const Motion& motion) {
  QuaternionVector mean;
  for (int j = 0; j < skeleton.num_joints(); ++j) mean.push_back(MeanLocalRotation(motion, j));
  return mean;
}

}  // namespace mocapsolve
