#include "problems/marker_solve/calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include <Eigen/Dense>

#include "kinematics/forward_kinematics.h"
#include "kinematics/quote_token.h"
#include "kinematics/unlabelled_label.h"
#include "problems/marker_solve/subject_checks.h"

namespace mocapsolve {
namespace {

// Joint frames of the matched motion frames, and the matching marker frames.
struct MatchedFrames {
  int first_motion = 0;
  int count = 0;
  int offset = 0;
  std::vector<FkData> fk;  // fk[i] for motion frame first_motion + i.
  int marker_frame(int i) const { return first_motion + i + offset; }
};

Status MatchFrames(const Skeleton& skeleton, const Motion& motion,
                   const MarkerTrajectories& trajectories, const CalibrationOptions& options,
                   MatchedFrames* matched) {
  Status status = ValidateMotion(skeleton, motion);
  if (!status.ok()) return status;
  const long long k = options.frame_offset;
  const long long first = std::max<long long>(0, -k);
  const long long end =
      std::min<long long>(motion.num_frames(), static_cast<long long>(trajectories.num_frames()) - k);
  if (end <= first) {
    return Status::Error("no overlapping frames: motion has " + std::to_string(motion.num_frames()) +
                         ", markers " + std::to_string(trajectories.num_frames()) +
                         ", frame_offset " + std::to_string(options.frame_offset));
  }
  matched->first_motion = static_cast<int>(first);
  matched->count = static_cast<int>(end - first);
  matched->offset = options.frame_offset;
  matched->fk.assign(matched->count, FkData(skeleton));
  for (int i = 0; i < matched->count; ++i) {
    ForwardKinematics(skeleton, motion.frames[matched->first_motion + i], &matched->fk[i]);
  }
  return Status::Ok();
}

// Matched frames where trajectory marker m is valid (indices into matched.fk).
std::vector<int> ValidFrames(const MatchedFrames& matched, const MarkerTrajectories& trajectories, int m) {
  std::vector<int> frames;
  for (int i = 0; i < matched.count; ++i) {
    if (trajectories.valid(matched.marker_frame(i), m)) frames.push_back(i);
  }
  return frames;
}

// Mean local position of marker m in joint j's frame and the spread about it.
void LocalMeanAndSpread(const MatchedFrames& matched, const MarkerTrajectories& trajectories, int m,
                        const std::vector<int>& frames, int j, Eigen::Vector3d* mean, double* mean_sq) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i : frames) {
    const FkData& fk = matched.fk[i];
    sum += fk.world_rotations[j].conjugate() *
           (trajectories.position(matched.marker_frame(i), m) - fk.world_positions[j]);
  }
  *mean = sum / static_cast<double>(frames.size());
  double sq = 0.0;
  for (int i : frames) {
    const FkData& fk = matched.fk[i];
    const Eigen::Vector3d local = fk.world_rotations[j].conjugate() *
                                  (trajectories.position(matched.marker_frame(i), m) - fk.world_positions[j]);
    sq += (local - *mean).squaredNorm();
  }
  *mean_sq = sq / static_cast<double>(frames.size());
}

// Least-squares offsets of a blended marker (K attachments) with fixed joints/weights.
void FitOffsets(const MatchedFrames& matched, const MarkerTrajectories& trajectories, int m,
                const std::vector<int>& frames, MarkerSpec* spec) {
  const int k = static_cast<int>(spec->attachments.size());
  if (k == 1) {
    const MarkerAttachment& a = spec->attachments[0];
    double unused;
    Eigen::Vector3d mean;
    LocalMeanAndSpread(matched, trajectories, m, frames, a.joint, &mean, &unused);
    // x = w (p + R z) with w = 1 after normalization; divide anyway for clarity.
    spec->attachments[0].offset = mean / a.weight;
    return;
  }
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(3 * k, 3 * k);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * k);
  Eigen::MatrixXd row_block(3, 3 * k);
  for (int i : frames) {
    const FkData& fk = matched.fk[i];
    Eigen::Vector3d b = trajectories.position(matched.marker_frame(i), m);
    for (int a = 0; a < k; ++a) {
      const MarkerAttachment& at = spec->attachments[a];
      row_block.middleCols<3>(3 * a) = at.weight * fk.world_rotations[at.joint].toRotationMatrix();
      b -= at.weight * fk.world_positions[at.joint];
    }
    normal.noalias() += row_block.transpose() * row_block;
    rhs.noalias() += row_block.transpose() * b;
  }
  const Eigen::VectorXd z = normal.completeOrthogonalDecomposition().solve(rhs);
  for (int a = 0; a < k; ++a) spec->attachments[a].offset = z.segment<3>(3 * a);
}

// Fills per-marker statistics and the overall RMS for result->marker_set.
void Evaluate(const MatchedFrames& matched, const MarkerTrajectories& trajectories,
              const std::vector<int>& trajectory_index, CalibrationResult* result) {
  const MarkerSet& set = result->marker_set;
  result->markers.assign(set.num_markers(), CalibratedMarker());
  double total_sq = 0.0;
  int samples = 0;
  for (int s = 0; s < set.num_markers(); ++s) {
    CalibratedMarker& out = result->markers[s];
    out.label = set.label(s);
    out.trajectory_index = trajectory_index[s];
    double sq = 0.0;
    for (int i = 0; i < matched.count; ++i) {
      const int f = matched.marker_frame(i);
      if (!trajectories.valid(f, out.trajectory_index)) continue;
      const double e = (set.Position(s, matched.fk[i]) - trajectories.position(f, out.trajectory_index)).norm();
      sq += e * e;
      out.max_error = std::max(out.max_error, e);
      ++out.frames;
    }
    out.rms = out.frames > 0 ? std::sqrt(sq / out.frames) : 0.0;
    total_sq += sq;
    samples += out.frames;
  }
  result->first_motion_frame = matched.first_motion;
  result->matched_frames = matched.count;
  result->samples = samples;
  result->rms = samples > 0 ? std::sqrt(total_sq / samples) : 0.0;
}

std::string MarkerName(const MarkerTrajectories& trajectories, int m) {
  return SplitSubjectPrefix(trajectories.label(m), trajectories.subject_prefixes).name;
}

}  // namespace

void TransformMarkers(const MarkerFileToModel& transform, const LengthUnit& new_unit,
                      MarkerTrajectories* trajectories) {
  for (int f = 0; f < trajectories->num_frames(); ++f) {
    for (int m = 0; m < trajectories->num_markers(); ++m) {
      if (!trajectories->valid(f, m)) continue;
      trajectories->SetSample(f, m, transform.Apply(trajectories->position(f, m)),
                              static_cast<float>(trajectories->residual(f, m) * transform.scale),
                              trajectories->camera_mask(f, m));
    }
  }
  trajectories->unit = new_unit;
}

Status CalibrateMarkers(const Skeleton& skeleton, const Motion& motion,
                        const MarkerTrajectories& trajectories, const CalibrationOptions& options,
                        const MarkerSet* attachments, CalibrationResult* result) {
  MatchedFrames matched;
  Status status = MatchFrames(skeleton, motion, trajectories, options, &matched);
  if (!status.ok()) return status;
  std::vector<int> candidates = options.candidate_joints;
  if (candidates.empty()) {
    for (int j = 0; j < skeleton.num_joints(); ++j) candidates.push_back(j);
  }
  for (int j : candidates) {
    if (j < 0 || j >= skeleton.num_joints()) {
      return Status::Error("candidate joint " + std::to_string(j) + " is not in the skeleton");
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  const int min_frames = std::max(1, options.min_valid_frames);

  CalibrationResult out;
  std::vector<MarkerSpec> specs;
  std::vector<int> trajectory_index;
  std::vector<std::pair<int, double>> runner_up;
  if (attachments == nullptr) {
    std::set<std::string> names;
    for (int m = 0; m < trajectories.num_markers(); ++m) {
      const std::string name = MarkerName(trajectories, m);
      if (IsUnlabelledLabel(name)) {
        out.skipped.push_back(trajectories.label(m) + ": unlabelled point");
        continue;
      }
      if (names.count(name) != 0) {
        out.skipped.push_back(trajectories.label(m) + ": label " + QuoteToken(name) + " repeats (several subjects?)");
        continue;
      }
      const std::vector<int> frames = ValidFrames(matched, trajectories, m);
      if (static_cast<int>(frames.size()) < min_frames) {
        out.skipped.push_back(trajectories.label(m) + ": valid in " + std::to_string(frames.size()) +
                              " matched frames (need " + std::to_string(min_frames) + ")");
        continue;
      }
      // Scale for the absolute tie tolerance: mean distance from the root.
      double scale = 0.0;
      for (int i : frames) {
        scale += (trajectories.position(matched.marker_frame(i), m) - matched.fk[i].world_positions[0]).norm();
      }
      scale /= frames.size();
      std::vector<double> spread(candidates.size());
      std::vector<Eigen::Vector3d> means(candidates.size());
      for (size_t c = 0; c < candidates.size(); ++c) {
        LocalMeanAndSpread(matched, trajectories, m, frames, candidates[c], &means[c], &spread[c]);
      }
      // With max_bone_distance, plausible joints only: the marker's mean local position
      // within the skin distance of the joint's bone (a toe marker does not ride on a
      // hip); when none qualifies, the joint with the nearest bone. Joints tied on the
      // spread (moving together in this motion, e.g. a forearm no marker has moved yet
      // and its upper arm) are told apart by the nearest bone, not the lowest index.
      std::vector<double> distance(candidates.size(), 0.0);
      for (size_t c = 0; c < candidates.size(); ++c) distance[c] = DistanceToBone(skeleton, candidates[c], means[c]);
      if (options.max_bone_distance > 0.0) {
        bool any = false;
        for (size_t c = 0; c < candidates.size(); ++c) any |= distance[c] <= options.max_bone_distance;
        const size_t nearest = std::min_element(distance.begin(), distance.end()) - distance.begin();
        for (size_t c = 0; c < candidates.size(); ++c) {
          const bool allowed = any ? distance[c] <= options.max_bone_distance : c == nearest;
          if (!allowed) spread[c] = std::numeric_limits<double>::infinity();
        }
      }
      const double best = *std::min_element(spread.begin(), spread.end());
      const double tie = best * (1.0 + options.tie_tolerance) + 1e-18 * scale * scale;
      size_t chosen = candidates.size();
      int second = -1;
      double second_spread = std::numeric_limits<double>::infinity();
      for (size_t c = 0; c < candidates.size(); ++c) {
        if (spread[c] <= tie) {
          // Among tied joints: the nearest bone (with max_bone_distance), else the ancestor
          // unless a tied joint's bone is clearly nearer (tie_nearer_factor).
          const double factor = options.max_bone_distance > 0.0 ? 1.0 : options.tie_nearer_factor;
          if (chosen == candidates.size() || (factor > 0.0 && factor * distance[c] < distance[chosen])) chosen = c;
        } else if (spread[c] < second_spread) {
          second_spread = spread[c];
          second = candidates[c];
        }
      }
      names.insert(name);
      specs.push_back({name, {{candidates[chosen], 1.0, means[chosen]}}});
      trajectory_index.push_back(m);
      runner_up.emplace_back(second, second < 0 ? 0.0 : std::sqrt(second_spread));
    }
  } else {
    std::vector<bool> used(trajectories.num_markers(), false);
    for (int s = 0; s < attachments->num_markers(); ++s) {
      const std::string& label = attachments->label(s);
      const int m = trajectories.FindMarker(label);
      if (m < 0) {
        out.skipped.push_back(label + ": not in the marker file");
        continue;
      }
      used[m] = true;
      const std::vector<int> frames = ValidFrames(matched, trajectories, m);
      if (static_cast<int>(frames.size()) < min_frames) {
        out.skipped.push_back(label + ": valid in " + std::to_string(frames.size()) +
                              " matched frames (need " + std::to_string(min_frames) + ")");
        continue;
      }
      MarkerSpec spec = attachments->marker(s);
      FitOffsets(matched, trajectories, m, frames, &spec);
      specs.push_back(std::move(spec));
      trajectory_index.push_back(m);
      runner_up.emplace_back(-1, 0.0);
    }
    for (int m = 0; m < trajectories.num_markers(); ++m) {
      if (!used[m]) out.skipped.push_back(trajectories.label(m) + ": not in the marker set");
    }
  }
  if (specs.empty()) return Status::Error("no marker could be calibrated");
  status = MarkerSet::Create(skeleton, std::move(specs), &out.marker_set);
  if (!status.ok()) return status;
  Evaluate(matched, trajectories, trajectory_index, &out);
  for (size_t s = 0; s < out.markers.size(); ++s) {
    out.markers[s].runner_up = runner_up[s].first;
    out.markers[s].runner_up_rms = runner_up[s].second;
  }
  *result = std::move(out);
  return Status::Ok();
}

Status EvaluateMarkerSet(const Skeleton& skeleton, const Motion& motion,
                         const MarkerTrajectories& trajectories, const MarkerSet& marker_set,
                         const CalibrationOptions& options, CalibrationResult* result) {
  MatchedFrames matched;
  Status status = MatchFrames(skeleton, motion, trajectories, options, &matched);
  if (!status.ok()) return status;
  CalibrationResult out;
  std::vector<MarkerSpec> specs;
  std::vector<int> trajectory_index;
  for (int s = 0; s < marker_set.num_markers(); ++s) {
    const int m = trajectories.FindMarker(marker_set.label(s));
    if (m < 0) {
      out.skipped.push_back(marker_set.label(s) + ": not in the marker file");
      continue;
    }
    specs.push_back(marker_set.marker(s));
    trajectory_index.push_back(m);
  }
  status = MarkerSet::Create(skeleton, std::move(specs), &out.marker_set);
  if (!status.ok()) return status;
  Evaluate(matched, trajectories, trajectory_index, &out);
  *result = std::move(out);
  return Status::Ok();
}

Status FindMarkerAxes(const Skeleton& skeleton, const Motion& motion,
                      const MarkerTrajectories& file_axes_trajectories,
                      const CalibrationOptions& options, const MarkerSet* attachments,
                      Eigen::Matrix3d* model_from_file, std::vector<double>* rms_per_candidate) {
  const std::vector<Eigen::Matrix3d> candidates = AllAxisRotations();
  std::vector<double> rms(candidates.size(), std::numeric_limits<double>::infinity());
  Status last_error = Status::Error("no axis candidate could be calibrated");
  size_t best = candidates.size();
  for (size_t c = 0; c < candidates.size(); ++c) {
    MarkerTrajectories rotated = file_axes_trajectories;
    MarkerFileToModel transform;
    transform.rotation = candidates[c];
    TransformMarkers(transform, rotated.unit, &rotated);
    CalibrationResult result;
    const Status status = CalibrateMarkers(skeleton, motion, rotated, options, attachments, &result);
    if (!status.ok()) {
      last_error = status;
      continue;
    }
    rms[c] = result.rms;
    if (best == candidates.size() || rms[c] < rms[best]) best = c;
  }
  if (rms_per_candidate != nullptr) *rms_per_candidate = rms;
  if (best == candidates.size()) return last_error;
  *model_from_file = candidates[best];
  return Status::Ok();
}

}  // namespace mocapsolve
