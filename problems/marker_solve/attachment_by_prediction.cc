#include "problems/marker_solve/attachment_by_prediction.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "problems/marker_solve/leave_one_out.h"
#include "problems/marker_solve/subject_checks.h"

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

// The median of `values` (infinity when empty); reorders them.
double MedianOf(std::vector<double>* values) {
  if (values->empty()) return std::numeric_limits<double>::infinity();
  std::nth_element(values->begin(), values->begin() + values->size() / 2, values->end());
  return (*values)[values->size() / 2];
}

// score(set) of the header over the markers `group`; `medians` (may be null) gets each
// marker's own median, parallel to group.
Status GroupScore(const Skeleton& skeleton, const MarkerSet& set, const std::vector<std::vector<Eigen::Vector3d>>& scored,
                  const MarkerSolveOptions& solve, const std::vector<int>& group, double* score,
                  std::vector<double>* medians = nullptr) {
  std::vector<double> errors;
  if (medians != nullptr) medians->clear();
  for (int n : group) {
    const size_t first = errors.size();
    const Status status = AppendErrors(skeleton, set, scored, solve, n, &errors);
    if (!status.ok()) return status;
    std::vector<double> own(errors.begin() + first, errors.end());
    if (medians != nullptr) medians->push_back(MedianOf(&own));
  }
  *score = MedianOf(&errors);
  return Status::Ok();
}

// Every k-th frame of `observed`, k = ceil(frames / max_frames).
std::vector<std::vector<Eigen::Vector3d>> ScoredFrames(const std::vector<std::vector<Eigen::Vector3d>>& observed,
                                                       int max_frames) {
  const int frames = static_cast<int>(observed.size());
  const int step = std::max(1, (frames + std::max(max_frames, 1) - 1) / std::max(max_frames, 1));
  std::vector<std::vector<Eigen::Vector3d>> scored;
  for (int f = 0; f < frames; f += step) scored.push_back(observed[f]);
  return scored;
}

// The limb of joint a (ChooseLimbBlends): up from a while a joint is its parent's only child.
int LimbTop(const Skeleton& skeleton, int a) {
  int top = a;
  while (skeleton.parent(top) >= 0) {
    const int p = skeleton.parent(top);
    int children = 0;
    for (int c = p + 1; c < skeleton.subtree_end(p); ++c) children += skeleton.parent(c) == p;
    if (children != 1) break;
    top = p;
  }
  return top;
}

// The limb's group: every marker with an attachment on a joint of top's subtree.
std::vector<int> LimbGroup(const Skeleton& skeleton, const std::vector<MarkerSpec>& specs, int top) {
  std::vector<int> group;
  for (int n = 0; n < static_cast<int>(specs.size()); ++n) {
    for (const MarkerAttachment& a : specs[n].attachments) {
      if (skeleton.IsAncestorOrSelf(top, a.joint)) {
        group.push_back(n);
        break;
      }
    }
  }
  return group;
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

std::vector<std::pair<int, int>> HingeBlendCandidates(const Skeleton& skeleton, const MarkerSet& markers,
                                                      double max_distance, double max_fraction, int max_dofs) {
  std::vector<std::pair<int, int>> pairs(markers.num_markers(), {-1, -1});
  // Whether z's projection on the bone from a's origin to `end` lies within max_fraction
  // of the bone's length of its `distal` (else proximal) end; a bone of no length: yes.
  const auto near_end = [max_fraction](const Eigen::Vector3d& z, const Eigen::Vector3d& end, bool distal) {
    const double length = end.norm();
    if (length <= 0.0) return true;
    const double along = z.dot(end) / length;
    return (distal ? length - along : along) <= max_fraction * length;
  };
  for (int m = 0; m < markers.num_markers(); ++m) {
    if (markers.marker(m).attachments.size() != 1) continue;
    const int a = markers.marker(m).attachments[0].joint;
    const Eigen::Vector3d& z = markers.marker(m).attachments[0].offset;
    double best = max_distance;
    // a's own axis: its longest segment from its origin (BoneSegments).
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    for (const auto& [from, to] : BoneSegments(skeleton, a)) {
      if (from.isZero() && to.norm() > axis.norm()) axis = to;
    }
    if (skeleton.parent(a) >= 0 && skeleton.num_rotation_dofs(a) > 0 && skeleton.num_rotation_dofs(a) <= max_dofs &&
        z.norm() <= best &&
        near_end(z, axis, false)) {
      best = z.norm();
      pairs[m] = {skeleton.parent(a), a};
    }
    // Depth-first over a's rigid body, as BoneSegments: (joint, a_from_joint).
    std::vector<std::pair<int, Eigen::Isometry3d>> stack = {{a, Eigen::Isometry3d::Identity()}};
    while (!stack.empty()) {
      const auto [k, frame] = stack.back();
      stack.pop_back();
      for (int c = k + 1; c < skeleton.subtree_end(k); ++c) {
        if (skeleton.parent(c) != k || skeleton.has_translation_channels(c)) continue;
        if (skeleton.num_rotation_dofs(c) == 0) {
          Eigen::Isometry3d child = frame;
          child.translate(skeleton.offset(c));
          child.rotate(skeleton.rest_rotation(c));
          stack.emplace_back(c, child);
        } else if (skeleton.num_rotation_dofs(c) <= max_dofs && (frame * skeleton.offset(c) - z).norm() <= best &&
                   near_end(z, frame * skeleton.offset(c), true)) {
          best = (frame * skeleton.offset(c) - z).norm();
          pairs[m] = {a, c};
        }
      }
    }
  }
  return pairs;
}

double JointBendRange(const Motion& motion, int joint, int max_frames) {
  const int frames = motion.num_frames();
  const int step = std::max(1, (frames + std::max(max_frames, 1) - 1) / std::max(max_frames, 1));
  std::vector<Eigen::Quaterniond> rotations;
  for (int f = 0; f < frames; f += step) rotations.push_back(motion.frames[f].rotations[joint]);
  double range = 0.0;
  for (size_t i = 0; i < rotations.size(); ++i) {
    for (size_t k = i + 1; k < rotations.size(); ++k) range = std::max(range, rotations[i].angularDistance(rotations[k]));
  }
  return range;
}

void DropHingesThatHoldStill(const Motion& motion, double min_bend, int max_frames,
                             std::vector<std::pair<int, int>>* pairs) {
  std::vector<double> bend;  // Per hinge joint, computed once (-1: not yet).
  for (std::pair<int, int>& pair : *pairs) {
    if (pair.second < 0) continue;
    if (static_cast<int>(bend.size()) <= pair.second) bend.resize(pair.second + 1, -1.0);
    if (bend[pair.second] < 0.0) bend[pair.second] = JointBendRange(motion, pair.second, max_frames);
    if (bend[pair.second] < min_bend) pair = {-1, -1};
  }
}

Status ChooseAmongAttachments(const Skeleton& skeleton, const std::vector<std::vector<Eigen::Vector3d>>& observed,
                              const std::vector<std::vector<AttachmentChoice>>& alternatives,
                              const MarkerSolveOptions& solve, const AttachmentByPredictionOptions& options,
                              MarkerSet* markers, std::vector<AttachmentMove>* moves) {
  if (static_cast<int>(alternatives.size()) != markers->num_markers()) {
    return Status::Error("attachment by prediction: one list of alternatives per marker expected");
  }
  const std::vector<std::vector<Eigen::Vector3d>> scored = ScoredFrames(observed, options.max_frames);
  std::vector<MarkerSpec> specs, chosen;
  for (int m = 0; m < markers->num_markers(); ++m) specs.push_back(markers->marker(m));
  chosen = specs;
  std::vector<AttachmentMove> decided;
  for (int m = 0; m < markers->num_markers(); ++m) {
    if (alternatives[m].empty() || specs[m].attachments.size() != 1) continue;
    AttachmentMove move;
    move.marker = m;
    move.from = specs[m].attachments[0].joint;
    std::vector<int> joints = {move.from};  // Of m's attachment and its alternatives.
    for (const AttachmentChoice& choice : alternatives[m]) {
      for (const MarkerAttachment& a : choice) joints.push_back(a.joint);
    }
    std::vector<int> group = {m};
    for (int n = 0; n < markers->num_markers(); ++n) {
      if (n == m) continue;
      for (const MarkerAttachment& a : specs[n].attachments) {
        if (std::find(joints.begin(), joints.end(), a.joint) != joints.end()) {
          group.push_back(n);
          break;
        }
      }
    }
    Status status = GroupScore(skeleton, *markers, scored, solve, group, &move.from_score);
    if (!status.ok()) return status;
    move.to_score = std::numeric_limits<double>::infinity();
    for (const AttachmentChoice& choice : alternatives[m]) {
      std::vector<MarkerSpec> moved_specs = specs;
      moved_specs[m].attachments = choice;
      MarkerSet moved_set;
      double score = 0.0;
      status = MarkerSet::Create(skeleton, moved_specs, &moved_set);
      if (status.ok()) status = GroupScore(skeleton, moved_set, scored, solve, group, &score);
      if (!status.ok()) return status;
      if (score < move.to_score) {
        move.to_score = score;
        move.to_attachments = moved_set.marker(m).attachments;
        move.to = choice.front().joint;
      }
    }
    move.moved = move.to_score < move.from_score;
    if (move.moved) chosen[m].attachments = move.to_attachments;
    decided.push_back(move);
  }
  Status status = MarkerSet::Create(skeleton, std::move(chosen), markers);
  if (!status.ok()) return status;
  if (moves != nullptr) *moves = std::move(decided);
  return Status::Ok();
}

Status ChooseLimbBlends(const Skeleton& skeleton, const std::vector<std::vector<Eigen::Vector3d>>& observed,
                        const std::vector<AttachmentChoice>& blends, const MarkerSolveOptions& solve,
                        const AttachmentByPredictionOptions& options, MarkerSet* markers,
                        std::vector<AttachmentMove>* moves) {
  const int count = markers->num_markers();
  if (static_cast<int>(blends.size()) != count) return Status::Error("limb blends: one entry per marker expected");
  const std::vector<std::vector<Eigen::Vector3d>> scored = ScoredFrames(observed, options.max_frames);
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < count; ++m) specs.push_back(markers->marker(m));
  std::vector<MarkerSpec> chosen = specs;
  std::vector<std::pair<int, std::vector<int>>> limbs;  // (top, its candidates).
  for (int m = 0; m < count; ++m) {
    if (blends[m].empty() || specs[m].attachments.size() != 1) continue;
    const int top = LimbTop(skeleton, blends[m].front().joint);
    auto limb = std::find_if(limbs.begin(), limbs.end(), [top](const auto& l) { return l.first == top; });
    if (limb == limbs.end()) limb = limbs.insert(limbs.end(), {top, {}});
    limb->second.push_back(m);
  }
  std::vector<AttachmentMove> decided;
  for (const auto& [top, candidates] : limbs) {
    const std::vector<int> group = LimbGroup(skeleton, specs, top);
    std::vector<MarkerSpec> current = specs;
    MarkerSet set;
    Status status = MarkerSet::Create(skeleton, current, &set);
    double base = 0.0;
    std::vector<double> base_medians;
    if (status.ok()) status = GroupScore(skeleton, set, scored, solve, group, &base, &base_medians);
    if (!status.ok()) return status;
    std::vector<double> tried(candidates.size(), std::numeric_limits<double>::infinity());
    std::vector<bool> accepted(candidates.size(), false);
    for (double score = base;;) {
      int best = -1;
      double best_score = score;
      for (size_t i = 0; i < candidates.size(); ++i) {
        if (accepted[i]) continue;
        std::vector<MarkerSpec> trial = current;
        trial[candidates[i]].attachments = blends[candidates[i]];
        double trial_score = 0.0;
        std::vector<double> medians;
        status = MarkerSet::Create(skeleton, trial, &set);
        if (status.ok()) status = GroupScore(skeleton, set, scored, solve, group, &trial_score, &medians);
        if (!status.ok()) return status;
        tried[i] = std::min(tried[i], trial_score);
        bool harmless = true;
        for (size_t k = 0; k < group.size(); ++k) {
          harmless &= medians[k] - base_medians[k] <= options.limb_rise * base;
          if (group[k] == candidates[i]) harmless &= medians[k] <= (1.0 - options.blend_own_gain) * base_medians[k];
        }
        if (harmless && trial_score < best_score) {
          best = static_cast<int>(i);
          best_score = trial_score;
        }
      }
      if (best < 0) break;
      accepted[best] = true;
      current[candidates[best]].attachments = blends[candidates[best]];
      score = best_score;
    }
    for (size_t i = 0; i < candidates.size(); ++i) {
      const int m = candidates[i];
      AttachmentMove move;
      move.marker = m;
      move.from = specs[m].attachments[0].joint;
      move.to = blends[m].front().joint;
      move.from_score = base;
      move.to_score = tried[i];
      move.to_attachments = blends[m];
      move.moved = accepted[i];
      if (move.moved) chosen[m].attachments = blends[m];
      decided.push_back(move);
    }
  }
  Status status = MarkerSet::Create(skeleton, std::move(chosen), markers);
  if (!status.ok()) return status;
  if (moves != nullptr) *moves = std::move(decided);
  return Status::Ok();
}

Status ChooseAttachmentsByPrediction(const Skeleton& skeleton, const std::vector<std::vector<Eigen::Vector3d>>& observed,
                                     const std::vector<MarkerAttachment>& alternative, const MarkerSolveOptions& solve,
                                     const AttachmentByPredictionOptions& options, MarkerSet* markers,
                                     std::vector<AttachmentMove>* moves) {
  if (static_cast<int>(alternative.size()) != markers->num_markers()) {
    return Status::Error("attachment by prediction: one alternative per marker expected");
  }
  std::vector<std::vector<AttachmentChoice>> alternatives(alternative.size());
  for (size_t m = 0; m < alternative.size(); ++m) {
    if (alternative[m].joint >= 0) alternatives[m] = {{{alternative[m].joint, 1.0, alternative[m].offset}}};
  }
  return ChooseAmongAttachments(skeleton, observed, alternatives, solve, options, markers, moves);
}

}  // namespace mocapsolve
