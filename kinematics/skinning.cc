#include "kinematics/skinning.h"

namespace mocapsolve {

void ComputeSkinningTransforms(const SkinnedMesh& mesh, const FkData& fk,
                               std::vector<Eigen::Isometry3d>* transforms) {
  const int nj = mesh.num_joints();
  transforms->resize(nj);
  for (int j = 0; j < nj; ++j) {
    Eigen::Isometry3d world_from_joint = Eigen::Isometry3d::Identity();
    world_from_joint.linear() = fk.world_rotations[j].toRotationMatrix();
    world_from_joint.translation() = fk.world_positions[j];
    (*transforms)[j] = world_from_joint * mesh.joint_from_bind(j);
  }
}

Eigen::Vector3d SkinPosition(const SkinnedMesh& mesh,
                             const std::vector<Eigen::Isometry3d>& transforms, int vertex) {
  const Eigen::Vector3d rest = mesh.rest_positions().col(vertex);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = mesh.weight_begin(vertex); k < mesh.weight_end(vertex); ++k) {
    sum += mesh.weight(k) * (transforms[mesh.weight_joint(k)] * rest);
  }
  return sum;
}

Eigen::Vector3d SkinNormal(const SkinnedMesh& mesh,
                           const std::vector<Eigen::Isometry3d>& transforms, int vertex) {
  const Eigen::Vector3d rest = mesh.rest_normals().col(vertex);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = mesh.weight_begin(vertex); k < mesh.weight_end(vertex); ++k) {
    sum += mesh.weight(k) * (transforms[mesh.weight_joint(k)].linear() * rest);
  }
  return sum;
}

void SkinMesh(const SkinnedMesh& mesh, const std::vector<Eigen::Isometry3d>& transforms,
              Eigen::Matrix3Xd* positions, Eigen::Matrix3Xd* normals) {
  const int nv = mesh.num_vertices();
  positions->resize(3, nv);
  for (int i = 0; i < nv; ++i) positions->col(i) = SkinPosition(mesh, transforms, i);
  if (normals != nullptr && mesh.has_normals()) {
    normals->resize(3, nv);
    for (int i = 0; i < nv; ++i) normals->col(i) = SkinNormal(mesh, transforms, i);
  }
}

}  // namespace mocapsolve
