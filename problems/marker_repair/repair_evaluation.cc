#include "problems/marker_repair/repair_evaluation.h"

#include <chrono>
#include <cmath>
#include <functional>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/sequence_solver.h"
#include "signal/baseline_gap_fill.h"

namespace mocapsolve {
namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Joint errors of `motion` against `truth`.
void ScoreJoints(const Skeleton& skeleton, const Motion& truth, const Motion& motion, RepairEvaluationRow* row) {
  FkData a(skeleton), b(skeleton);
  double position = 0.0, rotation = 0.0;
  for (int f = 0; f < truth.num_frames(); ++f) {
    ForwardKinematics(skeleton, truth.frames[f], &a);
    ForwardKinematics(skeleton, motion.frames[f], &b);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      position += (a.world_positions[j] - b.world_positions[j]).norm();
      rotation += AngularDistance(a.world_rotations[j], b.world_rotations[j]);
    }
  }
  const double samples = std::max(1.0, static_cast<double>(truth.num_frames()) * skeleton.num_joints());
  row->joint_position_error = position / samples;
  row->joint_rotation_error = rotation / samples;
}

// Marker errors over the damaged samples, and velocity jumps at the edges of damaged runs.
void ScoreMarkers(const MarkerObservations& clean, const MarkerObservations& x, const CorruptionMask& mask,
                  RepairEvaluationRow* row) {
  double sum = 0.0, sum_sq = 0.0, kind_sum[kNumDamageKinds] = {};
  int kind_count[kNumDamageKinds] = {};
  const int frames = static_cast<int>(clean.size());
  const int markers = frames > 0 ? static_cast<int>(clean[0].size()) : 0;
  for (int f = 0; f < frames; ++f) {
    for (int m = 0; m < markers; ++m) {
      if (mask[f][m] == 0) continue;
      ++row->damaged_samples;
      if (!x[f][m].allFinite() || !clean[f][m].allFinite()) continue;
      const double e = (x[f][m] - clean[f][m]).norm();
      ++row->covered_samples;
      sum += e;
      sum_sq += e * e;
      row->marker_error_max = std::max(row->marker_error_max, e);
      const int k = DamageKindIndex(mask[f][m]);
      if (k < 0) continue;
      kind_sum[k] += e;
      ++kind_count[k];
    }
  }
  for (int k = 0; k < kNumDamageKinds; ++k) row->kind_error[k] = kind_count[k] > 0 ? kind_sum[k] / kind_count[k] : 0.0;
  if (row->covered_samples > 0) {
    row->marker_error_mean = sum / row->covered_samples;
    row->marker_error_rms = std::sqrt(sum_sq / row->covered_samples);
  }
  // |v_in - v_out| at an edge between frames a (outside) and b (inside), c beyond a.
  double jumps = 0.0;
  int edges = 0;
  auto edge = [&](int m, int c, int a, int b) {
    if (c < 0 || c >= frames || b < 0 || b >= frames) return;
    const Eigen::Vector3d jump = (x[b][m] - x[a][m]) - (x[a][m] - x[c][m]);
    if (!jump.allFinite()) return;
    jumps += jump.norm();
    ++edges;
  };
  for (int m = 0; m < markers; ++m) {
    for (int f = 0; f < frames; ++f) {
      if (mask[f][m] == 0) continue;
      int last = f;
      while (last + 1 < frames && mask[last + 1][m] != 0) ++last;
      edge(m, f - 2, f - 1, f);
      edge(m, last + 2, last + 1, last);
      f = last;
    }
  }
  row->velocity_jump = edges > 0 ? jumps / edges : 0.0;
}

// Which samples of the corrupted markers x0 the method's markers x changed, against the mask.
void ScoreDetection(const MarkerObservations& clean, const MarkerObservations& x0, const MarkerObservations& x,
                    const CorruptionMask& mask, RepairEvaluationRow* row) {
  const int unlabelled = DamageKindIndex('u');
  for (size_t f = 0; f < x0.size(); ++f) {
    for (size_t m = 0; m < x0[f].size(); ++m) {
      const int k = DamageKindIndex(mask[f][m]);
      if (!x0[f][m].allFinite()) {  // Missing in X: detected when filled (unlabelled: restored).
        if (k < 0) continue;
        ++row->kind_samples[k];
        if (k == unlabelled ? x[f][m] == clean[f][m] : x[f][m].allFinite()) ++row->kind_detected[k];
        continue;
      }
      const bool changed = !(x[f][m].array() == x0[f][m].array()).all();
      if (k >= 0) ++row->kind_samples[k];
      if (!changed) continue;
      ++row->changed_samples;
      if (k >= 0) {
        ++row->kind_detected[k];
      } else {
        ++row->changed_undamaged_samples;
      }
    }
  }
}

}  // namespace

Status EvaluateRepair(const Skeleton& skeleton, const MarkerSet& markers, const MarkerObservations& clean,
                      const MarkerObservations& corrupted, const CorruptionMask& mask,
                      const RepairOptions& options, std::vector<RepairEvaluationRow>* rows,
                      const UnlabelledDamage* unlabelled) {
  rows->clear();
  if (Status status = CheckRepairObservations(markers, clean); !status.ok()) return status;
  UnlabelledPoints points;
  if (unlabelled != nullptr && unlabelled->tracks.num_markers() > 0) {
    if (unlabelled->tracks.num_frames() != static_cast<int>(clean.size()) ||
        unlabelled->source.size() != static_cast<size_t>(unlabelled->tracks.num_markers())) {
      return Status::Error("unlabelled tracks and markers differ in frame or track count");
    }
    points.names = unlabelled->tracks.labels();
    points.points = TrajectoryObservations(unlabelled->tracks);
  }
  if (clean.size() != corrupted.size() || clean.size() != mask.size()) {
    return Status::Error("clean markers, corrupted markers and mask differ in frame count");
  }
  for (size_t f = 0; f < clean.size(); ++f) {
    if (clean[f].size() != static_cast<size_t>(markers.num_markers()) ||
        corrupted[f].size() != clean[f].size() || mask[f].size() != clean[f].size()) {
      return Status::Error("frame " + std::to_string(f) + ": marker counts differ");
    }
  }
  Motion truth;
  SequenceSolveReport sequence;
  Status status = SolveSequence(skeleton, markers, clean, options.naive, RestPose(skeleton), &truth, &sequence);
  if (!status.ok()) return Status::Error("solving the clean markers: " + status.message());

  RepairEvaluationRow row;
  row.method = "clean";
  ScoreMarkers(clean, clean, mask, &row);  // Marker errors 0; the natural velocity jump.
  rows->push_back(row);

  // A fill of the corrupted markers, then the per-frame solve.
  auto evaluate_fill = [&](const char* name, const std::function<void(MarkerTrajectories*)>& fill) -> Status {
    const auto start = std::chrono::steady_clock::now();
    MarkerTrajectories x = ObservationTrajectories(markers, corrupted);
    if (fill) fill(&x);
    const MarkerObservations filled = TrajectoryObservations(x);
    Motion motion;
    Status solved = SolveSequence(skeleton, markers, filled, options.naive, RestPose(skeleton), &motion, &sequence);
    if (!solved.ok()) return Status::Error(std::string(name) + ": " + solved.message());
    RepairEvaluationRow r;
    r.method = name;
    r.seconds = Seconds(start);
    ScoreJoints(skeleton, truth, motion, &r);
    ScoreMarkers(clean, filled, mask, &r);
    ScoreDetection(clean, corrupted, filled, mask, &r);
    rows->push_back(r);
    return Status::Ok();
  };
  status = evaluate_fill("original", nullptr);
  if (status.ok()) status = evaluate_fill("polynomial", [](MarkerTrajectories* x) { FillGapsPolynomial(x); });
  if (status.ok()) status = evaluate_fill("linear", [](MarkerTrajectories* x) { FillGapsLinear(x); });
  if (status.ok()) status = evaluate_fill("pca", [](MarkerTrajectories* x) { FillGapsPca(PcaFillOptions(), x); });
  if (!status.ok()) return status;

  const auto start = std::chrono::steady_clock::now();
  MarkerObservations repaired;
  Motion motion;
  RepairReport report;
  RepairIntermediates intermediates;
  status = RepairMarkers(skeleton, markers, corrupted, points, options, &repaired, &motion, &report, &intermediates);
  if (!status.ok()) return status;
  const double repair_seconds = Seconds(start);
  RepairEvaluationRow reference;
  reference.method = "reference only";
  for (const RepairStageTime& t : report.timings) {
    if (t.stage.find("eference") != std::string::npos) reference.seconds += t.seconds;
  }
  ScoreJoints(skeleton, truth, intermediates.reference, &reference);
  ScoreMarkers(clean, intermediates.reconstructed, mask, &reference);
  ScoreDetection(clean, corrupted, intermediates.reconstructed, mask, &reference);
  rows->push_back(reference);
  RepairEvaluationRow ours;
  ours.method = "ours";
  ours.seconds = repair_seconds;
  ScoreJoints(skeleton, truth, motion, &ours);
  ScoreMarkers(clean, repaired, mask, &ours);
  ScoreDetection(clean, corrupted, repaired, mask, &ours);
  for (const UnlabelledAssignment& a : report.unlabelled) {
    if (a.marker != unlabelled->source[a.track]) {
      ours.unlabelled_false_samples += a.last - a.first + 1;
      continue;
    }
    for (int f = a.first; f <= a.last; ++f) ours.unlabelled_assigned_samples += mask[f][a.marker] == 'u';
  }
  rows->push_back(ours);
  return Status::Ok();
}

Status EvaluateRepairTrial(const Skeleton& skeleton, const MarkerSet& markers, const MarkerObservations& clean,
                           const CorruptionOptions& damage, const RepairOptions& options,
                           std::vector<RepairEvaluationRow>* rows) {
  if (Status status = CheckRepairObservations(markers, clean); !status.ok()) return status;
  MarkerTrajectories x = ObservationTrajectories(markers, clean);
  x.unit = skeleton.unit();
  CorruptionMask mask;
  UnlabelledDamage unlabelled;
  CorruptMarkers(damage, &x, &mask, &unlabelled);
  return EvaluateRepair(skeleton, markers, clean, TrajectoryObservations(x), mask, options, rows, &unlabelled);
}

}  // namespace mocapsolve
