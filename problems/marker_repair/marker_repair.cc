#include "problems/marker_repair/marker_repair.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "kinematics/forward_kinematics.h"
#include "kinematics/marker_trajectories.h"
#include "problems/marker_repair/marker_residual_model.h"
#include "problems/marker_repair/unlabelled_assignment.h"
#include "problems/marker_solve/sequence_solver.h"
#include "signal/bad_interval_detection.h"
#include "signal/gap_cleanup.h"
#include "signal/gap_fill.h"
#include "signal/offset_kriging.h"
#include "signal/rough_run_extension.h"

namespace mocapsolve {
namespace {

using Observations = std::vector<std::vector<Eigen::Vector3d>>;

double RmsOver(const Skeleton& skeleton, const MarkerSet& markers, const Motion& motion,
               const Observations& observed) {
  double sum = 0.0;
  long n = 0;
  for (size_t f = 0; f < observed.size(); ++f) {
    int count = 0;
    const double rms = RmsMarkerError(skeleton, markers, motion.frames[f], observed[f], &count);
    sum += rms * rms * count;
    n += count;
  }
  return n > 0 ? std::sqrt(sum / n) : 0.0;
}

// Velocity difference |(X - R)'| at frame f (backward difference), or +inf if unknown.
double SlopeDifference(const MarkerTrajectories& x, const MarkerTrajectories& r, int m, int f) {
  if (f < 1 || f >= x.num_frames() || !x.valid(f, m) || !x.valid(f - 1, m)) {
    return std::numeric_limits<double>::infinity();
  }
  return ((x.position(f, m) - x.position(f - 1, m)) - (r.position(f, m) - r.position(f - 1, m))).norm();
}

// Smart trimming: on each side of each gap that holds a sample missing from `unflagged`
// (the capture's own gaps, and labels a swap left without a sample), cut k <= trim_max
// valid frames, k chosen so that the new edge sample has the smallest slope difference
// to the reference. Gaps made only of detected outliers are not trimmed: the detector
// bounded them, and on a clean take trimming turned one outlying sample into up to 241
// replaced ones.
int TrimAroundGaps(const MarkerTrajectories& reference, int trim_max, const MarkerTrajectories& unflagged,
                   MarkerTrajectories* x) {
  int trimmed = 0;
  for (const Gap& gap : FindGaps(*x)) {
    const int m = gap.marker;
    bool natural = false;
    for (int f = gap.first; f <= gap.last && !natural; ++f) natural = !unflagged.valid(f, m);
    if (!natural) continue;
    if (gap.first > 0) {
      int best = 0;
      double best_difference = SlopeDifference(*x, reference, m, gap.first - 1);
      for (int k = 1; k <= trim_max && gap.first - 1 - k >= 0 && x->valid(gap.first - 1 - k, m); ++k) {
        const double d = SlopeDifference(*x, reference, m, gap.first - 1 - k);
        if (d < best_difference) best_difference = d, best = k;
      }
      for (int k = 0; k < best; ++k) x->SetMissing(gap.first - 1 - k, m);
      trimmed += best;
    }
    if (gap.last + 1 < x->num_frames()) {
      int best = 0;
      double best_difference = SlopeDifference(*x, reference, m, gap.last + 2);
      for (int k = 1; k <= trim_max && gap.last + 1 + k < x->num_frames() && x->valid(gap.last + 1 + k, m); ++k) {
        const double d = SlopeDifference(*x, reference, m, gap.last + 2 + k);
        if (d < best_difference) best_difference = d, best = k;
      }
      for (int k = 0; k < best; ++k) x->SetMissing(gap.last + 1 + k, m);
      trimmed += best;
    }
  }
  return trimmed;
}

bool SameSample(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return a.allFinite() ? a == b : !b.allFinite();
}

// Step 7: the per-frame solve of `repaired`, reusing `naive` (the solve of `observed`
// with the same options) wherever the two problems coincide: a frame whose markers are
// unchanged, warm-started and pulled from a pose equal to naive's previous one, has
// naive's solution. After a changed frame the solve goes on until it rejoins naive
// (joint positions within `tolerance`).
// Frames [begin, end) of step 7; motion->frames[begin - 1] (or naive's first frame) is
// the previous pose. Returns the number of frames solved.
int ResolveChangedRange(const Skeleton& skeleton, const MarkerSet& markers, const Observations& observed,
                        const Observations& repaired, const Motion& naive, const MarkerSolveOptions& options,
                        double tolerance, size_t begin, size_t end, Motion* motion) {
  int resolved = 0;
  MarkerFrameSolver solver(skeleton, markers, options);
  FkData fk(skeleton), fk_naive(skeleton);
  bool in_sync = true;
  for (size_t f = begin; f < end; ++f) {
    bool changed = false;
    for (int m = 0; m < markers.num_markers() && !changed; ++m) {
      changed = !SameSample(repaired[f][m], observed[f][m]);
    }
    if (!changed && in_sync) continue;
    // The previous pose; at the start of a range, naive's (the other range may be
    // writing the frame before it).
    Pose pose = f > begin ? motion->frames[f - 1] : naive.frames[begin > 0 ? begin - 1 : 0];
    FrameSolveReport frame;
    if (solver.Solve(repaired[f], &pose, &frame).ok()) motion->frames[f] = pose;
    ++resolved;
    in_sync = false;
    if (!changed) {
      ForwardKinematics(skeleton, motion->frames[f], &fk);
      ForwardKinematics(skeleton, naive.frames[f], &fk_naive);
      double difference = 0.0;
      for (int j = 0; j < skeleton.num_joints(); ++j) {
        difference = std::max(difference, (fk.world_positions[j] - fk_naive.world_positions[j]).norm());
      }
      in_sync = difference <= tolerance;
      if (in_sync) motion->frames[f] = naive.frames[f];
    }
  }
  return resolved;
}

// The clip is solved in two halves, the second starting from naive's pose before its
// first frame, as if the frames before it had rejoined naive; with `parallel` the halves
// run on two threads. The halves are the same either way, so the result does not depend
// on the thread count (a batch runs its takes single-threaded side by side).
Status ResolveChangedFrames(const Skeleton& skeleton, const MarkerSet& markers, const Observations& observed,
                            const Observations& repaired, const Motion& naive,
                            const MarkerSolveOptions& options, double tolerance, bool parallel, Motion* motion,
                            int* resolved) {
  *motion = naive;
  const size_t n = repaired.size(), half = n >= 64 ? n / 2 : n;
  int second = 0;
  auto solve_second = [&] {
    second = ResolveChangedRange(skeleton, markers, observed, repaired, naive, options, tolerance, half, n, motion);
  };
  std::thread worker;
  if (half < n && parallel) worker = std::thread(solve_second);
  *resolved = ResolveChangedRange(skeleton, markers, observed, repaired, naive, options, tolerance, 0, half, motion);
  if (worker.joinable()) {
    worker.join();
  } else if (half < n) {
    solve_second();
  }
  *resolved += second;
  MakeSignContinuous(motion);
  return Status::Ok();
}

class StageClock {
 public:
  explicit StageClock(RepairReport* report) : report_(report), start_(std::chrono::steady_clock::now()) {}
  void Lap(const char* stage) {
    const auto now = std::chrono::steady_clock::now();
    report_->timings.push_back({stage, std::chrono::duration<double>(now - start_).count()});
    start_ = now;
  }

 private:
  RepairReport* report_;
  std::chrono::steady_clock::time_point start_;
};

// X^ = LBS(Y^, Z): every marker's position on the reference, every frame.
Observations ReconstructMarkers(const Skeleton& skeleton, const MarkerSet& markers, const Motion& reference) {
  Observations out(reference.frames.size(), std::vector<Eigen::Vector3d>(markers.num_markers()));
  FkData fk(skeleton);
  for (size_t f = 0; f < reference.frames.size(); ++f) {
    ForwardKinematics(skeleton, reference.frames[f], &fk);
    for (int m = 0; m < markers.num_markers(); ++m) out[f][m] = markers.Position(m, fk);
  }
  return out;
}

}  // namespace

MarkerTrajectories ObservationTrajectories(const MarkerSet& markers, const Observations& observed) {
  std::vector<std::string> labels;
  for (int m = 0; m < markers.num_markers(); ++m) labels.push_back(markers.label(m));
  MarkerTrajectories out(labels, static_cast<int>(observed.size()));
  for (size_t f = 0; f < observed.size(); ++f) {
    for (int m = 0; m < markers.num_markers(); ++m) {
      if (observed[f][m].allFinite()) out.SetSample(static_cast<int>(f), m, observed[f][m]);
    }
  }
  return out;
}

Observations TrajectoryObservations(const MarkerTrajectories& trajectories) {
  Observations out(trajectories.num_frames(), std::vector<Eigen::Vector3d>(trajectories.num_markers()));
  for (int f = 0; f < trajectories.num_frames(); ++f) {
    for (int m = 0; m < trajectories.num_markers(); ++m) out[f][m] = trajectories.position(f, m);
  }
  return out;
}

bool RepairOptions::IsValid(std::string* error) const {
  if (!naive.IsValid(error)) return false;
  if (reference_kind == ReferenceKind::kClip && !reference.IsValid(error)) return false;
  if (reference_kind == ReferenceKind::kTracker && !tracker.IsValid(error)) return false;
  for (const double v : {dp_max, dr_max_rad}) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      return *error = "dp_max and dr_max must be positive and finite", false;
    }
  }
  // <= 0 selects a default for these; NaN or inf selects nothing.
  for (const double v : {resync_tolerance, outlier_distance, velocity_clamp}) {
    if (!std::isfinite(v)) {
      return *error = "resync tolerance, outlier distance and velocity clamp must be finite", false;
    }
  }
  if (!(outlier_mads > 0.0) || !std::isfinite(outlier_mads) || !std::isfinite(outlier_min_distance) ||
      !std::isfinite(swap_radius)) {
    return *error = "outlier_mads must be positive and finite, outlier_min_distance and swap_radius finite", false;
  }
  if (swap_min_frames < 1) return *error = "swap_min_frames must be >= 1", false;
  if (edge_samples < 1 || edge_samples > 1000) return *error = "edge_samples must be in [1, 1000]", false;
  if (fill_samples < 1 || fill_samples > 1000) return *error = "fill_samples must be in [1, 1000]", false;
  if (!(refit_rough_factor > 0.0) || !std::isfinite(refit_rough_factor)) {
    return *error = "refit_rough_factor must be positive and finite", false;
  }
  if (!(rough_extension_factor >= 0.0) || !std::isfinite(rough_extension_factor)) {
    return *error = "rough_extension_factor must be >= 0 and finite", false;
  }
  if (!std::isfinite(unlabelled_min_distance) || !std::isfinite(unlabelled_max_distance)) {
    return *error = "unlabelled_min_distance and unlabelled_max_distance must be finite", false;
  }
  if (unlabelled_min_frames < 1) return *error = "unlabelled_min_frames must be >= 1", false;
  if (trim_max < 0 || small_track < 0 || small_gap < 0) {
    return *error = "trim_max, small_track and small_gap must be >= 0 frames", false;
  }
  return true;
}

Status CheckRepairObservations(const MarkerSet& markers, const Observations& observed) {
  if (observed.empty()) return Status::Error("the take has no frames (nothing to repair)");
  for (size_t f = 0; f < observed.size(); ++f) {
    if (observed[f].size() != static_cast<size_t>(markers.num_markers())) {
      return Status::Error("frame " + std::to_string(f) + ": " + std::to_string(observed[f].size()) +
                           " markers, the marker set has " + std::to_string(markers.num_markers()));
    }
  }
  return Status::Ok();
}

Status RepairMarkers(const Skeleton& skeleton, const MarkerSet& markers, const Observations& observed,
                     const RepairOptions& options, Observations* repaired, Motion* motion,
                     RepairReport* report, RepairIntermediates* intermediates, const RepairProgress& progress) {
  return RepairMarkers(skeleton, markers, observed, UnlabelledPoints(), options, repaired, motion, report,
                       intermediates, progress);
}

Status RepairMarkers(const Skeleton& skeleton, const MarkerSet& markers, const Observations& observed,
                     const UnlabelledPoints& unlabelled, const RepairOptions& options, Observations* repaired,
                     Motion* motion, RepairReport* report, RepairIntermediates* intermediates,
                     const RepairProgress& progress) {
  if (std::string error; !options.IsValid(&error)) return Status::Error(error);
  if (Status status = CheckRepairObservations(markers, observed); !status.ok()) return status;
  if (unlabelled.num_tracks() > 0 && unlabelled.points.size() != observed.size()) {
    return Status::Error("unlabelled points: " + std::to_string(unlabelled.points.size()) + " frames, markers " +
                         std::to_string(observed.size()));
  }
  for (const auto& frame : unlabelled.points) {
    if (frame.size() != static_cast<size_t>(unlabelled.num_tracks())) {
      return Status::Error("unlabelled points: a frame's point count differs from the track names'");
    }
  }
  *report = RepairReport();
  StageClock clock(report);
  // 1. Naive solve and 2. robust reference (the tracker needs no naive solve, so with two
  // threads the two run side by side).
  Motion naive, reference;
  SequenceSolveReport sequence;
  Status status = Status::Ok(), reference_status = Status::Ok();
  const int num_frames = static_cast<int>(observed.size());
  std::function<void(int)> naive_progress;
  if (progress) {
    naive_progress = [&](int done) {
      progress(options.reference_kind == ReferenceKind::kTracker ? "IK + reference" : "IK", done, num_frames);
    };
  }
  if (options.reference_kind == ReferenceKind::kTracker) {
    SequenceSolveReport tracker_report;
    auto track = [&] {
      reference_status = SolveSequence(skeleton, markers, observed, options.tracker, RestPose(skeleton),
                                       &reference, &tracker_report);
    };
    std::thread tracker;
    if (options.parallel) tracker = std::thread(track);
    status = SolveSequence(skeleton, markers, observed, options.naive, RestPose(skeleton), &naive, &sequence,
                           naive_progress);
    if (options.parallel) {
      tracker.join();
    } else {
      track();
    }
    if (!status.ok()) return status;
    if (!reference_status.ok()) return reference_status;
    clock.Lap(options.parallel ? "IK (naive) + reference (robust tracker), in parallel"
                               : "IK (naive) + reference (robust tracker)");
  } else {
    status = SolveSequence(skeleton, markers, observed, options.naive, RestPose(skeleton), &naive, &sequence,
                           naive_progress);
    if (!status.ok()) return status;
    clock.Lap("IK (naive solve)");
    reference = naive;
    ClipSolveReport clip;
    status = SolveClip(skeleton, markers, observed, options.reference, &reference, &clip);
    if (!status.ok()) return status;
    clock.Lap("Reference solve (robust clip)");
  }
  report->naive_rms = RmsOver(skeleton, markers, naive, observed);
  report->naive_unconverged_frames = sequence.unconverged_frames;
  report->reference_rms = RmsOver(skeleton, markers, reference, observed);
  // 3. Marker reconstruction.
  Observations reconstructed = ReconstructMarkers(skeleton, markers, reference);
  MarkerTrajectories reference_paths = ObservationTrajectories(markers, reconstructed);
  clock.Lap("Marker Reconstruction");
  // 3b. Residual model.
  MarkerTrajectories x = ObservationTrajectories(markers, observed);
  const double outlier = options.outlier_distance > 0.0 ? options.outlier_distance : options.dp_max;
  ResidualModelOptions model_options;
  model_options.robust = options.robust_outliers;
  model_options.mads = options.outlier_mads;
  model_options.min_distance = options.outlier_min_distance > 0.0 ? options.outlier_min_distance : outlier / 4.0;
  model_options.max_distance = outlier;
  model_options.fixed_distance = outlier;
  MarkerResidualModel model = FitMarkerResidualModel(skeleton, markers, reference, reconstructed, x, model_options);
  clock.Lap("Residual Model");
  // Re-solves of changed frames stop where the solution rejoins the earlier one.
  const double resync_tolerance = options.resync_tolerance > 0.0 ? options.resync_tolerance : options.dp_max * 1e-3;
  // 3c. Swaps: relabel; 3d. unlabelled points labelled; then redo the naive solve where
  // the samples changed.
  const MarkerTrajectories captured = x;
  const Observations* input = &observed;
  Observations relabelled;
  const bool assigning = options.assign_unlabelled && unlabelled.num_tracks() > 0;
  if (options.undo_swaps) {
    SwapDetectionOptions swap_options;
    swap_options.radius = options.swap_radius > 0.0 ? options.swap_radius : 3.0 * options.dp_max;
    swap_options.min_frames = options.swap_min_frames;
    report->swaps = UndoSwaps(model, swap_options, &x);
    if (!report->swaps.empty()) relabelled = TrajectoryObservations(x);
    // The robust tracker leans toward the swapped labels while a swap lasts (on a bone
    // that one marker pins, such as the thumb's, it follows them), so the relabelled
    // samples would be judged outliers against it: it is redone where the samples changed,
    // until it rejoins the earlier solution, and X^ with it.
    // A swap from the first frame misled the tracker's start (its orientation search):
    // then the whole tracker is run again.
    if (!report->swaps.empty() && options.reference_kind == ReferenceKind::kTracker) {
      Motion redone;
      if (report->swaps.front().first == 0) {
        SequenceSolveReport tracker_report;
        status = SolveSequence(skeleton, markers, relabelled, options.tracker, RestPose(skeleton), &redone,
                               &tracker_report);
      } else {
        int resolved = 0;
        status = ResolveChangedFrames(skeleton, markers, observed, relabelled, reference, options.tracker,
                                      resync_tolerance, options.parallel, &redone, &resolved);
      }
      if (!status.ok()) return status;
      reference = std::move(redone);
      reconstructed = ReconstructMarkers(skeleton, markers, reference);
      reference_paths = ObservationTrajectories(markers, reconstructed);
    }
    if (assigning) clock.Lap("Swap Detection");
  }
  if (assigning) {
    UnlabelledAssignmentOptions assign;
    assign.mads = options.outlier_mads;
    assign.min_distance = options.unlabelled_min_distance > 0.0 ? options.unlabelled_min_distance : outlier / 2.0;
    assign.max_distance = options.unlabelled_max_distance > 0.0 ? options.unlabelled_max_distance : 1.25 * outlier;
    assign.min_frames = options.unlabelled_min_frames;
    report->unlabelled = AssignUnlabelledPoints(model, unlabelled, assign, &x);
    if (!report->unlabelled.empty()) relabelled = TrajectoryObservations(x);
  }
  if (!report->swaps.empty() || !report->unlabelled.empty()) {
    Motion solved;
    int resolved = 0;
    status = ResolveChangedFrames(skeleton, markers, observed, relabelled, naive, options.naive, resync_tolerance,
                                  options.parallel, &solved, &resolved);
    if (!status.ok()) return status;
    naive = std::move(solved);
    input = &relabelled;
    // The soft-tissue residual was fitted with the swapped samples in its window and
    // without the assigned ones.
    model = FitMarkerResidualModel(skeleton, markers, reference, reconstructed, x, model_options);
    // The reference followed the swapped labels: its parent frames do not judge the
    // relabelled samples (marker_residual_model.h).
    for (const MarkerSwap& swap : report->swaps) {
      for (int f = swap.first; f <= swap.last; ++f) {
        for (const auto& [from, to] : swap.from_to) model.absorbed[f][to] = 0;
      }
    }
  }
  if (assigning) {
    clock.Lap("Unlabelled Assignment");  // With the re-solve of the changed frames.
  } else if (options.undo_swaps) {
    clock.Lap("Swap Detection");
  }
  // 4. Gap detection.
  for (const Gap& gap : FindGaps(captured)) report->detected.push_back({gap.marker, gap.first, gap.last, "missing"});
  for (const MarkerSwap& swap : report->swaps) {
    for (const auto& [from, to] : swap.from_to) {
      report->detected.push_back({to, swap.first, swap.last, "swap"});
    }
  }
  for (const UnlabelledAssignment& a : report->unlabelled) {
    report->detected.push_back({a.marker, a.first, a.last, "unlabelled"});
  }
  std::vector<std::vector<char>> bad_joints;
  status = DetectBadJoints(skeleton, naive, reference, {options.dp_max, options.dr_max_rad}, &bad_joints);
  if (!status.ok()) return status;
  auto bad = BadMarkerSamples(markers, bad_joints);
  // A joint difference condemns a marker only where it moves the marker past its gate.
  FkData fk_naive(skeleton);
  for (int f = 0; f < x.num_frames(); ++f) {
    bool any = false;
    for (int m = 0; m < x.num_markers() && !any; ++m) any = bad[f][m];
    if (!any) continue;
    ForwardKinematics(skeleton, naive.frames[f], &fk_naive);
    for (int m = 0; m < x.num_markers(); ++m) {
      if (bad[f][m] && (markers.Position(m, fk_naive) - reconstructed[f][m]).norm() <= model.gate[m]) bad[f][m] = 0;
    }
  }
  MarkerTrajectories outliers_removed = x;
  for (int f = 0; f < x.num_frames(); ++f) {
    for (int m = 0; m < x.num_markers(); ++m) {
      if (x.valid(f, m) && model.Outlying(f, m, x.position(f, m))) outliers_removed.SetMissing(f, m);
    }
  }
  MarkerTrajectories flagged = outliers_removed;
  for (int f = 0; f < x.num_frames(); ++f) {
    for (int m = 0; m < x.num_markers(); ++m) {
      if (bad[f][m] && flagged.valid(f, m)) flagged.SetMissing(f, m);
    }
  }
  // Name each new gap by its first cause: swap (a label left without a sample), outlier,
  // else joint difference.
  for (const Gap& gap : FindGaps(flagged)) {
    bool natural = true, outlying = false, swapped = false;
    for (int f = gap.first; f <= gap.last; ++f) {
      natural &= !captured.valid(f, gap.marker);
      swapped |= captured.valid(f, gap.marker) && !x.valid(f, gap.marker);
      outlying |= x.valid(f, gap.marker) && !outliers_removed.valid(f, gap.marker);
    }
    if (!natural) {
      report->detected.push_back(
          {gap.marker, gap.first, gap.last, swapped ? "swap" : outlying ? "outlier" : "joint difference"});
    }
  }
  const MarkerTrajectories unflagged = x;
  x = flagged;
  clock.Lap("Gap Detection");
  // 5. Preprocessing, in the thesis' order.
  report->trimmed_samples = TrimAroundGaps(reference_paths, options.trim_max, unflagged, &x);
  report->removed_track_samples = RemoveSmallTracks(options.small_track, &x);
  MarkerTrajectories before_small = x;
  report->polynomial_samples = FillSmallGaps(options.small_gap, &x);
  for (const Gap& gap : FindGaps(before_small)) {
    if (x.valid(gap.first, gap.marker)) report->filled.push_back({gap.marker, gap.first, gap.last, "polynomial"});
  }
  clock.Lap("Gap Preprocessing");
  // 6. Marker filling from the reference.
  // The tracker leaned toward the samples now cut (its loss bounds the pull of each sample,
  // not of a displaced run of them): it is refitted without them where they were (the
  // trimmed samples kept), until it rejoins. A smooth run (a marker flown off, a ghost:
  // the removed samples' median |second difference| within refit_rough_factor times the
  // marker's own over its kept samples) and a gap without samples are filled from the
  // refitted X^; a rough run (noise, jitter), whose samples scatter about the true path
  // so that the robust solve averaged them, from X^ as solved (issue 16, BENCHMARKS.md).
  MarkerTrajectories refit_paths;
  const bool refit = options.refit_reference && options.reference_kind == ReferenceKind::kTracker;
  if (refit) {
    Motion refitted;
    int resolved = 0;
    status = ResolveChangedFrames(skeleton, markers, *input, TrajectoryObservations(flagged), reference,
                                  options.tracker, resync_tolerance, options.parallel, &refitted, &resolved);
    if (!status.ok()) return status;
    refit_paths = ObservationTrajectories(markers, ReconstructMarkers(skeleton, markers, refitted));
  }
  std::vector<double> own_roughness(x.num_markers(), -1.0);
  if (refit) {
    for (int m = 0; m < x.num_markers(); ++m) {
      own_roughness[m] = MedianSecondDifference(before_small, nullptr, m, 0, x.num_frames() - 1);
    }
  }
  auto is_rough = [&](const Gap& gap) {
    const double roughness = MedianSecondDifference(unflagged, nullptr, gap.marker, gap.first, gap.last);
    return refit && roughness >= 0.0 && roughness > options.refit_rough_factor * own_roughness[gap.marker];
  };
  // A rough run is cut whole: the samples beside it as rough as it (a noise run's ends and
  // small draws pass the gates), judged on the residual to X^ as solved
  // (signal/rough_run_extension.h); they leave the kriging's conditioning samples too.
  if (refit && options.rough_extension_factor > 0.0) {
    // The threshold is at least a tenth of the gates' floor (1 mm by default): a noise-free
    // marker's median is ~0, and the walk then cut the clean samples where X^ leaned toward
    // the run (the synthetic demo walk: 4-7 a side; on real takes the floor changes nothing).
    const double threshold_floor = 0.1 * model_options.min_distance;
    std::vector<double> own(x.num_markers(), std::numeric_limits<double>::quiet_NaN());  // Computed once needed.
    for (const Gap& gap : FindGaps(x)) {
      if (!is_rough(gap)) continue;
      double& own_level = own[gap.marker];
      if (std::isnan(own_level)) {
        own_level = MedianSecondDifference(before_small, &reference_paths, gap.marker, 0, x.num_frames() - 1);
      }
      if (own_level < 0.0) continue;
      const double threshold = std::max(options.rough_extension_factor * own_level, threshold_floor);
      report->rough_extension_samples +=
          ExtendRoughRun(gap, unflagged, reference_paths, threshold, options.trim_max, &x, &before_small);
    }
  }
  GapFillOptions fill;
  if (options.velocity_clamp > 0.0) fill.velocity_clamp = options.velocity_clamp;
  fill.edge_samples = options.edge_samples;
  // Kriging conditions on the samples that survived detection and preprocessing, not on
  // the small gaps' cubics nor on another gap's fill; one offset process per reference.
  OffsetKrigingOptions kriging;
  kriging.samples_per_side = options.fill_samples;
  std::vector<OffsetProcess> processes, refit_processes;
  if (options.fill == GapFillKind::kKriging) {
    status = EstimateOffsetProcesses(before_small, reference_paths, kriging, &processes);
    if (status.ok() && refit) status = EstimateOffsetProcesses(before_small, refit_paths, kriging, &refit_processes);
    if (!status.ok()) return status;
  }
  for (const Gap& gap : FindGaps(x)) {
    const bool from_refit = refit && !is_rough(gap);
    const MarkerTrajectories& paths = from_refit ? refit_paths : reference_paths;
    const std::vector<OffsetProcess>& offsets = from_refit ? refit_processes : processes;
    if (options.fill == GapFillKind::kKriging && offsets[gap.marker].valid) {
      status = FillGapByKriging(gap, before_small, paths, offsets[gap.marker], kriging, &x);
    } else {
      status = FillGapFromReference(gap, paths, fill, &x);
    }
    if (!status.ok()) return status;
    const bool whole = gap.first == 0 && gap.last + 1 == x.num_frames();
    report->filled.push_back({gap.marker, gap.first, gap.last, whole ? "reference only" : "reference"});
  }
  // Every sample is now valid; those never marked bad are the input's, bit for bit.
  *repaired = TrajectoryObservations(x);
  clock.Lap("Marker Filling");
  // 7. Re-solve.
  if (progress) progress("re-solve", 0, num_frames);
  status = ResolveChangedFrames(skeleton, markers, *input, *repaired, naive, options.naive, resync_tolerance,
                                options.parallel, motion, &report->resolved_frames);
  if (!status.ok()) return status;
  if (progress) progress("re-solve", num_frames, num_frames);
  report->repaired_rms = RmsOver(skeleton, markers, *motion, *repaired);
  clock.Lap("IK (re-solve)");
  if (intermediates != nullptr) {
    intermediates->naive = std::move(naive);
    intermediates->reference = std::move(reference);
    intermediates->reconstructed = std::move(reconstructed);
    intermediates->residual_model = std::move(model);
  }
  return Status::Ok();
}

}  // namespace mocapsolve
