#include "kinematics/kinematic_jacobians.h"

#include <cassert>

#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

void PrepareJacobian(const Skeleton& skeleton, PoseJacobian* jacobian) {
  jacobian->setZero(3, PoseTangentSize(skeleton));
}

}  // namespace

void AccumulateBlendedPointJacobian(const Skeleton& skeleton, const FkData& fk,
                                    const std::vector<BlendTerm>& terms,
                                    PoseJacobian* jacobian) {
  assert(jacobian->cols() == PoseTangentSize(skeleton));
  for (const BlendTerm& term : terms) {
    jacobian->leftCols<3>().diagonal().array() += term.weight;
    for (int j = term.joint; j >= 0; j = skeleton.parent(j)) {
      jacobian->middleCols<3>(RotationColumn(j)) +=
          term.weight * SkewSymmetric(fk.world_positions[j] - term.point_in_world) *
          fk.world_rotations[j].toRotationMatrix();
    }
  }
}

void JointPositionJacobian(const Skeleton& skeleton, const FkData& fk, int joint,
                           PoseJacobian* jacobian) {
  PrepareJacobian(skeleton, jacobian);
  AccumulateBlendedPointJacobian(skeleton, fk, {{joint, 1.0, fk.world_positions[joint]}},
                                 jacobian);
}

void SkinnedPositionJacobian(const Skeleton& skeleton, const SkinnedMesh& mesh,
                             const FkData& fk, const std::vector<Eigen::Isometry3d>& transforms,
                             int vertex, PoseJacobian* jacobian) {
  PrepareJacobian(skeleton, jacobian);
  std::vector<BlendTerm> terms;
  const Eigen::Vector3d rest = mesh.rest_positions().col(vertex);
  for (int k = mesh.weight_begin(vertex); k < mesh.weight_end(vertex); ++k) {
    const int b = mesh.weight_joint(k);
    terms.push_back({b, mesh.weight(k), transforms[b] * rest});
  }
  AccumulateBlendedPointJacobian(skeleton, fk, terms, jacobian);
}

void SkinnedNormalJacobian(const Skeleton& skeleton, const SkinnedMesh& mesh, const FkData& fk,
                           const std::vector<Eigen::Isometry3d>& transforms, int vertex,
                           PoseJacobian* jacobian) {
  PrepareJacobian(skeleton, jacobian);
  const Eigen::Vector3d rest = mesh.rest_normals().col(vertex);
  for (int k = mesh.weight_begin(vertex); k < mesh.weight_end(vertex); ++k) {
    const int b = mesh.weight_joint(k);
    const Eigen::Vector3d n_b = transforms[b].linear() * rest;
    for (int j = b; j >= 0; j = skeleton.parent(j)) {
      jacobian->middleCols<3>(RotationColumn(j)) -=
          mesh.weight(k) * SkewSymmetric(n_b) * fk.world_rotations[j].toRotationMatrix();
    }
  }
}

void RetractPose(const Eigen::VectorXd& tangent, Pose* pose) {
  const int nj = static_cast<int>(pose->rotations.size());
  assert(tangent.size() == 3 + 3 * nj);
  pose->translations[0] += tangent.head<3>();
  for (int j = 0; j < nj; ++j) {
    pose->rotations[j] = pose->rotations[j] * ExpMap(tangent.segment<3>(RotationColumn(j)));
  }
}

}  // namespace mocapsolve
