#include "problems/edit_propagation/pose_features.h"

#include <algorithm>
#include <cmath>

#include "kinematics/quote_token.h"
#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

// The log of a quaternion without LogMap's hemisphere choice: for a sign-continuous series
// the rotation vector then stays continuous when the angle passes pi (angles up to 2 pi).
Eigen::Vector3d ContinuousLog(const Eigen::Quaterniond& q) {
  const double n = q.vec().norm();
  if (n < 1e-8) return LogMap(q);  // Near +-identity: the hemisphere choice is moot.
  return (2.0 * std::atan2(n, q.w()) / n) * q.vec();
}

}  // namespace

Status PoseFeatures(const Skeleton& skeleton, const Motion& motion,
                    const PoseFeatureOptions& options, Eigen::MatrixXd* features) {
  if (motion.num_frames() == 0) return Status::Error("motion: no frames");
  Status status = ValidateMotion(skeleton, motion);
  if (!status.ok()) return status;
  std::vector<int> joints;
  if (options.joints.empty()) {
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      if (skeleton.num_rotation_dofs(j) > 0) joints.push_back(j);
    }
  } else {
    for (const std::string& name : options.joints) {
      const int j = skeleton.FindJoint(name);
      if (j < 0) return Status::Error("features.joints: no joint named " + QuoteToken(name));
      joints.push_back(j);
    }
  }
  if (joints.empty()) return Status::Error("features.joints: the skeleton has no rotating joint");
  if (!options.joint_weights.empty() && options.joint_weights.size() != joints.size()) {
    return Status::Error("features.joint_weights: expected " + std::to_string(joints.size()) +
                         " weights (one per joint), got " +
                         std::to_string(options.joint_weights.size()));
  }
  for (double w : options.joint_weights) {
    if (!(w >= 0.0) || !std::isfinite(w)) {
      return Status::Error("features.joint_weights: expected finite weights >= 0");
    }
  }
  if (!(options.temporal_weight >= 0.0) || !std::isfinite(options.temporal_weight)) {
    return Status::Error("features.temporal_weight: expected a finite value >= 0");
  }
  const bool temporal = options.temporal_weight > 0.0;
  if (temporal && !(motion.frame_rate > 0.0)) {
    return Status::Error("features.temporal_weight: the motion has no frame rate");
  }
  const int num_frames = motion.num_frames();
  const int dims = 3 * static_cast<int>(joints.size()) + (temporal ? 1 : 0);
  features->resize(num_frames, dims);
  std::vector<Eigen::Quaterniond> series(num_frames);
  for (size_t c = 0; c < joints.size(); ++c) {
    const int j = joints[c];
    for (int i = 0; i < num_frames; ++i) series[i] = motion.frames[i].rotations[j];
    if (series[0].w() < 0.0) series[0].coeffs() = -series[0].coeffs();
    MakeSignContinuous(&series);
    const double w = options.joint_weights.empty() ? 1.0 : options.joint_weights[c];
    for (int i = 0; i < num_frames; ++i) {
      features->block<1, 3>(i, 3 * c) = w * ContinuousLog(series[i]).transpose();
    }
  }
  if (temporal) {
    for (int i = 0; i < num_frames; ++i) {
      (*features)(i, dims - 1) = options.temporal_weight * i / motion.frame_rate;
    }
  }
  return Status::Ok();
}

double MedianStepDistance(const Eigen::MatrixXd& features) {
  const Eigen::Index n = features.rows();
  if (n < 2) return 0.0;
  std::vector<double> steps(n - 1);
  for (Eigen::Index i = 0; i + 1 < n; ++i) steps[i] = (features.row(i + 1) - features.row(i)).norm();
  auto middle = steps.begin() + steps.size() / 2;
  std::nth_element(steps.begin(), middle, steps.end());
  return *middle;
}

}  // namespace mocapsolve
