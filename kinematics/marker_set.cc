#include "kinematics/marker_set.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "kinematics/quote_token.h"
#include "kinematics/rotation.h"

namespace mocapsolve {

Status MarkerSet::Create(const Skeleton& skeleton, std::vector<MarkerSpec> markers,
                         MarkerSet* marker_set) {
  MarkerSet result;
  std::set<std::string> labels;
  for (MarkerSpec& spec : markers) {
    const std::string where = "marker " + QuoteToken(spec.label);
    if (spec.label.empty()) return Status::Error("marker with an empty label");
    if (!labels.insert(spec.label).second) return Status::Error(where + ": duplicate label");
    if (spec.attachments.empty()) return Status::Error(where + ": no attachment");
    if (!(spec.solve_weight > 0.0 && spec.solve_weight <= 1e6)) return Status::Error(where + ": solve weight not in (0, 1e6]");
    double total = 0.0;
    std::set<int> chain;
    for (const MarkerAttachment& a : spec.attachments) {
      if (a.joint < 0 || a.joint >= skeleton.num_joints()) {
        return Status::Error(where + ": joint index " + std::to_string(a.joint) +
                             " is not in the skeleton");
      }
      if (!a.offset.allFinite() || !std::isfinite(a.weight) || a.weight < 0.0) {
        return Status::Error(where + ": non-finite offset or bad weight");
      }
      total += a.weight;
      for (int j = a.joint; j >= 0; j = skeleton.parent(j)) chain.insert(j);
    }
    if (!(total > 0.0)) return Status::Error(where + ": weights sum to zero");
    for (MarkerAttachment& a : spec.attachments) a.weight /= total;
    result.influencing_joints_.emplace_back(chain.begin(), chain.end());
    result.markers_.push_back(std::move(spec));
  }
  *marker_set = std::move(result);
  return Status::Ok();
}

int MarkerSet::FindMarker(const std::string& label) const {
  for (int m = 0; m < num_markers(); ++m) {
    if (markers_[m].label == label) return m;
  }
  return -1;
}

Eigen::Vector3d MarkerSet::Position(int m, const FkData& fk) const {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (const MarkerAttachment& a : markers_[m].attachments) {
    x += a.weight * (fk.world_positions[a.joint] + fk.world_rotations[a.joint] * a.offset);
  }
  return x;
}

void MarkerSet::BlendTerms(int m, const FkData& fk, std::vector<BlendTerm>* terms) const {
  terms->clear();
  for (const MarkerAttachment& a : markers_[m].attachments) {
    terms->push_back(
        {a.joint, a.weight, fk.world_positions[a.joint] + fk.world_rotations[a.joint] * a.offset});
  }
}

void MarkerSetJacobian(const Skeleton& skeleton, const MarkerSet& markers, const FkData& fk,
                       std::vector<Eigen::Matrix3d>* rotations, Eigen::MatrixXd* jacobian) {
  const int nj = skeleton.num_joints();
  rotations->resize(nj);
  for (int j = 0; j < nj; ++j) (*rotations)[j] = fk.world_rotations[j].toRotationMatrix();
  jacobian->setZero(3 * markers.num_markers(), PoseTangentSize(skeleton));
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (const MarkerAttachment& a : markers.marker(m).attachments) {
      const Eigen::Vector3d p = fk.world_positions[a.joint] + (*rotations)[a.joint] * a.offset;
      jacobian->block<3, 3>(3 * m, 0).diagonal().array() += a.weight;
      for (int j = a.joint; j >= 0; j = skeleton.parent(j)) {
        jacobian->block<3, 3>(3 * m, RotationColumn(j)).noalias() +=
            a.weight * SkewSymmetric(fk.world_positions[j] - p) * (*rotations)[j];
      }
    }
  }
}

}  // namespace mocapsolve
