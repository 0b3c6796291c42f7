#include "kinematics/skinned_mesh.h"

#include <cmath>
#include <string>

namespace mocapsolve {

Status SkinnedMesh::Create(const Skeleton& skeleton, SkinnedMeshSpec spec, SkinnedMesh* mesh) {
  const int nv = static_cast<int>(spec.rest_positions.cols());
  const int nj = skeleton.num_joints();
  if (static_cast<int>(spec.influences.size()) != nv) {
    return Status::Error("skin: " + std::to_string(spec.influences.size()) +
                         " weight lists for " + std::to_string(nv) + " vertices");
  }
  if (spec.rest_normals.cols() != 0 && spec.rest_normals.cols() != nv) {
    return Status::Error("skin: normal count differs from vertex count");
  }
  if (spec.texcoords.cols() != 0 && spec.texcoords.cols() != nv) {
    return Status::Error("skin: texture coordinate count differs from vertex count");
  }
  if (static_cast<int>(spec.joint_from_bind.size()) != nj) {
    return Status::Error("skin: " + std::to_string(spec.joint_from_bind.size()) +
                         " inverse bind matrices for " + std::to_string(nj) + " joints");
  }
  if (!spec.rest_positions.allFinite() || !spec.rest_normals.allFinite() || !spec.texcoords.allFinite()) {
    return Status::Error("skin: non-finite rest position, normal or texture coordinate");
  }
  SkinnedMesh m;
  m.row_begin_.reserve(nv + 1);
  m.row_begin_.push_back(0);
  for (int i = 0; i < nv; ++i) {
    double total = 0.0;
    for (const SkinInfluence& inf : spec.influences[i]) {
      if (inf.joint < 0 || inf.joint >= nj || !std::isfinite(inf.weight) || inf.weight < 0.0) {
        return Status::Error("skin: vertex " + std::to_string(i) +
                             " has a bad joint index or weight");
      }
      total += inf.weight;
    }
    if (!(total > 0.0)) {
      return Status::Error("skin: vertex " + std::to_string(i) + " has no weight");
    }
    for (const SkinInfluence& inf : spec.influences[i]) {
      if (inf.weight == 0.0) continue;
      m.joints_.push_back(inf.joint);
      m.weights_.push_back(inf.weight / total);
    }
    m.row_begin_.push_back(static_cast<int>(m.joints_.size()));
  }
  m.rest_positions_ = std::move(spec.rest_positions);
  m.rest_normals_ = std::move(spec.rest_normals);
  m.texcoords_ = std::move(spec.texcoords);
  m.joint_from_bind_ = std::move(spec.joint_from_bind);
  *mesh = std::move(m);
  return Status::Ok();
}

double SkinnedMesh::CumulativeWeight(const Skeleton& skeleton, int vertex, int joint) const {
  double sum = 0.0;
  for (int k = weight_begin(vertex); k < weight_end(vertex); ++k) {
    if (skeleton.IsAncestorOrSelf(joint, joints_[k])) sum += weights_[k];
  }
  return sum;
}

}  // namespace mocapsolve
