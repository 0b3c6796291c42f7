#include "problems/marker_solve/locked_axes.h"

#include <limits>
#include <string>
#include <utility>

namespace mocapsolve {

std::vector<int> LockedAxisJoints(const Skeleton& skeleton, const MarkerSet& markers, int min_markers) {
  const int n = skeleton.num_joints();
  std::vector<int> on_joint(n, 0);
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (const MarkerAttachment& a : markers.marker(m).attachments) ++on_joint[a.joint];
  }
  std::vector<int> joints;
  for (int j = 1; j < n; ++j) {
    if (skeleton.num_rotation_dofs(j) != 2) continue;
    bool made_up_below = false;
    int below = 0;
    for (int k = j; k < skeleton.subtree_end(j); ++k) {
      if (k > j && skeleton.num_rotation_dofs(k) == 3) made_up_below = true;
      below += on_joint[k];
    }
    if (!made_up_below && below >= min_markers) joints.push_back(j);
  }
  return joints;
}

Status FreeLockedAxes(const Skeleton& skeleton, const std::vector<int>& joints, Skeleton* freed) {
  std::vector<JointSpec> specs;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    specs.push_back(skeleton.joint(j));
    specs.back().rotation_axes = skeleton.rotation_axes(j);
  }
  for (int j : joints) {
    if (j < 0 || j >= skeleton.num_joints() || skeleton.num_rotation_dofs(j) != 2) {
      return Status::Error("FreeLockedAxes: joint " + std::to_string(j) + " has not two rotation dofs");
    }
    JointSpec& spec = specs[j];
    const std::vector<int> axes = skeleton.rotation_axes(j);
    const int missing = 3 - axes[0] - axes[1];
    spec.rotation_axes = std::vector<int>{axes[0], missing, axes[1]};
    if (!spec.rotation_limits.empty()) {
      const double inf = std::numeric_limits<double>::infinity();
      spec.rotation_limits.insert(spec.rotation_limits.begin() + 1, {-inf, inf});
    }
    const Channel channel = static_cast<Channel>(static_cast<int>(Channel::kXrotation) + missing);
    bool has_channel = false;
    for (Channel c : spec.channels) has_channel = has_channel || c == channel;
    if (!spec.channels.empty() && !has_channel) spec.channels.push_back(channel);
  }
  return Skeleton::Create(std::move(specs), skeleton.end_sites(), skeleton.unit(), freed);
}

}  // namespace mocapsolve
