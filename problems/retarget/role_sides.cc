#include "problems/retarget/role_sides.h"

#include <string>
#include <vector>

namespace mocapsolve {

Eigen::Vector3d LeftOfCharacter(const Skeleton& skeleton, const SkinnedMesh& mesh, const HumanoidRoles& roles,
                                const Eigen::Matrix3d& world_from_bind) {
  const int nj = skeleton.num_joints();
  if (!roles.humanoid || mesh.num_joints() != nj) return Eigen::Vector3d::Zero();
  std::vector<int> side(nj, 0);  // +1 left, -1 right, 0 none; joints are parents first.
  std::vector<char> has_role(nj, 0);
  for (const auto& [role, joint] : roles.roles) {
    if (joint < 0 || joint >= nj) continue;
    has_role[joint] = 1;
    side[joint] = role.rfind("left_", 0) == 0 ? 1 : role.rfind("right_", 0) == 0 ? -1 : 0;
  }
  for (int j = 0; j < nj; ++j) {
    if (!has_role[j] && skeleton.parent(j) >= 0) side[j] = side[skeleton.parent(j)];
  }
  Eigen::Vector3d sum[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  int count[2] = {0, 0};
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    int heaviest = -1;
    double weight = -1.0;
    for (int k = mesh.weight_begin(v); k < mesh.weight_end(v); ++k) {
      if (mesh.weight(k) > weight) weight = mesh.weight(k), heaviest = mesh.weight_joint(k);
    }
    if (heaviest < 0 || side[heaviest] == 0) continue;
    const int s = side[heaviest] > 0 ? 0 : 1;
    sum[s] += mesh.rest_positions().col(v);
    ++count[s];
  }
  if (count[0] == 0 || count[1] == 0) return Eigen::Vector3d::Zero();
  return world_from_bind * (sum[0] / count[0] - sum[1] / count[1]);
}

}  // namespace mocapsolve
