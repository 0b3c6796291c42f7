#include "problems/marker_solve/attachment_by_prediction.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "problems/marker_solve/leave_one_out.h"

namespace mocapsolve {
namespace {

// Appends n's prediction errors on `scored` from the solve of the others with `set`
// (leave_one_out.h's, per frame only).
Status AppendErrors(const Skeleton& skeleton, const MarkerSet& set, const std::vector<std::vector<Eigen::Vector3d>>& scored,
                    const MarkerSolveOptions& solve, int n, std::vector<double>* errors) {
  LeaveOneOutOptions options;
  options.frame = solve;
  std::vector<double> own;
  const Status status = LeftOutPredictionErrors(skeleton, set, scored, n, options, &own);
  errors->insert(errors->end(), own.begin(), own.end());
  return status;
}

// score(set) of the header over the markers `group`.
Status GroupScore(const Skeleton& skeleton, const MarkerSet& set, const std::vector<std::vector<Eigen::Vector3d>>& scored,
                  const MarkerSolveOptions& solve, const std::vector<int>& group, double* score) {
  std::vector<double> errors;
  for (int n : group) {
    const Status status = AppendErrors(skeleton, set, scored, solve, n, &errors);
    if (!status.ok()) return status;
  }
  *score = std::numeric_limits<double>::infinity();
  if (errors.empty()) return Status::Ok();
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  *score = errors[errors.size() / 2];
  return Status::Ok();
}

}  // namespace

std::vector<int> PredictionCandidates(const Skeleton& skeleton, const CalibrationResult& result, double tolerance) {
  std::vector<int> alternative(result.marker_set.num_markers(), -1);
  if (!(tolerance > 0.0)) return alternative;
  for (int m = 0; m < result.marker_set.num_markers(); ++m) {
    const MarkerSpec& spec = result.marker_set.marker(m);
    const CalibratedMarker& c = result.markers[m];
    if (spec.attachments.size() != 1 || c.runner_up < 0) continue;
    const int j = spec.attachments[0].joint;
    const bool related = skeleton.parent(j) == c.runner_up || skeleton.parent(c.runner_up) == j;
    if (related && c.runner_up_rms <= (1.0 + tolerance) * c.rms) alternative[m] = c.runner_up;
  }
  return alternative;
}

std::vector<int> RigidClusterCandidates(const MarkerSet& markers, const std::vector<std::vector<int>>& clusters) {
  std::vector<int> alternative(markers.num_markers(), -1);
  for (const std::vector<int>& cluster : clusters) {
    if (cluster.size() < 3) continue;
    std::vector<int> joints;  // Of the cluster's markers.
    for (int n : cluster) {
      if (markers.marker(n).attachments.size() == 1) joints.push_back(markers.marker(n).attachments[0].joint);
    }
    for (int m : cluster) {
      if (markers.marker(m).attachments.size() != 1) continue;
      const int own = markers.marker(m).attachments[0].joint;
      for (int b : joints) {
        if (b != own && 2 * std::count(joints.begin(), joints.end(), b) > static_cast<long>(cluster.size())) {
          alternative[m] = b;
          break;
        }
      }
    }
  }
  return alternative;
}

Status ChooseAttachmentsByPrediction(const Skeleton& skeleton, const std::vector<std::vector<Eigen::Vector3d>>& observed,
                                     const std::vector<MarkerAttachment>& alternative, const MarkerSolveOptions& solve,
                                     const AttachmentByPredictionOptions& options, MarkerSet* markers,
                                     std::vector<AttachmentMove>* moves) {
  if (static_cast<int>(alternative.size()) != markers->num_markers()) {
    return Status::Error("attachment by prediction: one alternative per marker expected");
  }
  const int frames = static_cast<int>(observed.size());
  const int step = std::max(1, (frames + std::max(options.max_frames, 1) - 1) / std::max(options.max_frames, 1));
  std::vector<std::vector<Eigen::Vector3d>> scored;
  for (int f = 0; f < frames; f += step) scored.push_back(observed[f]);
  std::vector<MarkerSpec> specs, chosen;
  for (int m = 0; m < markers->num_markers(); ++m) specs.push_back(markers->marker(m));
  chosen = specs;
  std::vector<AttachmentMove> decided;
  for (int m = 0; m < markers->num_markers(); ++m) {
    if (alternative[m].joint < 0 || specs[m].attachments.size() != 1) continue;
    AttachmentMove move;
    move.marker = m;
    move.from = specs[m].attachments[0].joint;
    move.to = alternative[m].joint;
    std::vector<int> group = {m};
    for (int n = 0; n < markers->num_markers(); ++n) {
      if (n == m) continue;
      for (const MarkerAttachment& a : specs[n].attachments) {
        if (a.joint == move.from || a.joint == move.to) {
          group.push_back(n);
          break;
        }
      }
    }
    std::vector<MarkerSpec> moved_specs = specs;
    moved_specs[m].attachments = {{move.to, 1.0, alternative[m].offset}};
    MarkerSet moved_set;
    Status status = MarkerSet::Create(skeleton, moved_specs, &moved_set);
    if (status.ok()) status = GroupScore(skeleton, *markers, scored, solve, group, &move.from_score);
    if (status.ok()) status = GroupScore(skeleton, moved_set, scored, solve, group, &move.to_score);
    if (!status.ok()) return status;
    move.moved = move.to_score < move.from_score;
    if (move.moved) chosen[m] = moved_specs[m];
    decided.push_back(move);
  }
  Status status = MarkerSet::Create(skeleton, std::move(chosen), markers);
  if (!status.ok()) return status;
  if (moves != nullptr) *moves = std::move(decided);
  return Status::Ok();
}

}  // namespace mocapsolve
