#include "problems/retarget/stride_scale.h"

#include <string>

#include "kinematics/forward_kinematics.h"

namespace mocapsolve {

double LegLength(const Skeleton& skeleton, const std::vector<std::pair<int, int>>& thigh_foot) {
  FkData rest(skeleton);
  ForwardKinematics(skeleton, RestPose(skeleton), &rest);
  double sum = 0.0;
  int sides = 0;
  for (const auto& [thigh, foot] : thigh_foot) {
    if (thigh < 0 || foot < 0) continue;
    double length = 0.0;
    int joint = foot;
    while (joint > thigh) {  // Parents come first: the chain up from the foot.
      length += skeleton.offset(joint).norm();
      joint = skeleton.parent(joint);
    }
    // A foot that is not below the thigh (an IK bone under a root bone): the rest distance.
    if (joint != thigh) length = (rest.world_positions[foot] - rest.world_positions[thigh]).norm();
    sum += length;
    ++sides;
  }
  return sides > 0 ? sum / sides : 0.0;
}

void ScaleRootStride(double factor, Motion* motion) {
  if (motion->frames.empty()) return;
  const Eigen::Vector3d first = motion->frames[0].translations[0];
  for (Pose& pose : motion->frames) {
    Eigen::Vector3d& t = pose.translations[0];
    t.x() = first.x() + factor * (t.x() - first.x());
    t.z() = first.z() + factor * (t.z() - first.z());
  }
}

}  // namespace mocapsolve
