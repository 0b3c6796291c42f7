#include "kinematics/forward_kinematics.h"

#include <cassert>

namespace mocapsolve {

void ForwardKinematics(const Skeleton& skeleton, const Pose& pose, FkData* data) {
  const int n = skeleton.num_joints();
  assert(static_cast<int>(pose.rotations.size()) == n);
  assert(static_cast<int>(data->world_rotations.size()) == n);
  Eigen::Quaterniond* rotation = data->world_rotations.data();
  Eigen::Vector3d* position = data->world_positions.data();
  rotation[0] = skeleton.has_rest_rotation(0) ? skeleton.rest_rotation(0) * pose.rotations[0]
                                              : pose.rotations[0];
  position[0] = pose.translations[0];
  for (int j = 1; j < n; ++j) {
    const int p = skeleton.parent(j);
    position[j] = position[p] + rotation[p] * pose.translations[j];
    rotation[j] = skeleton.has_rest_rotation(j)
                      ? rotation[p] * (skeleton.rest_rotation(j) * pose.rotations[j])
                      : rotation[p] * pose.rotations[j];
  }
}

Vector3dVector EndSitePositions(const Skeleton& skeleton, const FkData& data) {
  Vector3dVector out;
  out.reserve(skeleton.end_sites().size());
  for (const EndSite& site : skeleton.end_sites()) {
    out.push_back(data.world_positions[site.parent] +
                  data.world_rotations[site.parent] * site.offset);
  }
  return out;
}

std::vector<Vector3dVector> ClipJointPositions(const Skeleton& skeleton, const Motion& motion) {
  std::vector<Vector3dVector> out;
  out.reserve(motion.frames.size());
  FkData data(skeleton);
  for (const Pose& pose : motion.frames) {
    ForwardKinematics(skeleton, pose, &data);
    out.push_back(data.world_positions);
  }
  return out;
}

}  // namespace mocapsolve
