#include "problems/retarget/foot_clearance.h"

#include <algorithm>
#include <limits>

#include "kinematics/forward_kinematics.h"
#include "kinematics/skinning.h"

namespace mocapsolve {

std::vector<double> FootRestClearances(const Skeleton& skeleton, const std::vector<int>& joints, const Pose& rest,
                                       const SkinnedMesh* mesh) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, rest, &fk);
  double floor = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : fk.world_positions) floor = std::min(floor, p.y());
  if (mesh != nullptr && mesh->num_vertices() > 0) {
    std::vector<Eigen::Isometry3d> transforms;
    ComputeSkinningTransforms(*mesh, fk, &transforms);
    Eigen::Matrix3Xd vertices;
    SkinMesh(*mesh, transforms, &vertices, nullptr);
    floor = std::min(floor, vertices.row(1).minCoeff());
  }
  std::vector<double> clearances;
  for (int j : joints) clearances.push_back(fk.world_positions[j].y() - floor);
  return clearances;
}

}  // namespace mocapsolve
