#include "problems/marker_repair/marker_repair.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <thread>

#include "kinematics/compact_motion.h"
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

// The marker's typical slope difference to the reference: the median over its frames.
double TypicalSlopeDifference(const MarkerTrajectories& x, const MarkerTrajectories& r, int m) {
  std::vector<double> d;
  for (int f = 1; f < x.num_frames(); ++f) {
    const double v = SlopeDifference(x, r, m, f);
    if (std::isfinite(v)) d.push_back(v);
  }
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

// A gap's edge whose slope difference is within this many times the marker's typical one
// is as good as the rest of its track: trimming stops there.
constexpr double kTrimTypicalFactor = 3.0;

// Smart trimming: on each side of each gap that holds a sample missing from `unflagged`
// (the capture's own gaps, and labels a swap left without a sample), cut k <= trim_max
// valid frames: the first k whose new edge sample's slope difference to the reference is
// typical of the marker (within kTrimTypicalFactor of its median), else the k of the
// smallest difference (the thesis' rule). Taking the smallest difference over all 120
// candidates cut clean samples far from a good edge: one missing sample of a clean track
// replaced 50-170 captured samples, up to 43 mm away from them (CMU 02_05 labelled from
// its raw points, BENCHMARKS.md). Gaps made only of detected outliers are not trimmed: the
// detector bounded them, and on a clean take trimming turned one outlying sample into up
// to 241 replaced ones. Relabelled samples (another label's capture, `captured`
// differing) are not trimmed either: the swap step judged them against the label's
// prediction, and a swap that begins or ends inside a gap would otherwise lose up to
// trim_max of them to a refill instead of keeping them bit for bit.
int TrimAroundGaps(const MarkerTrajectories& reference, int trim_max, const MarkerTrajectories& unflagged,
                   const MarkerTrajectories& captured, MarkerTrajectories* x) {
  auto trimmable = [&](int f, int m) {
    return x->valid(f, m) && captured.valid(f, m) && x->position(f, m) == captured.position(f, m);
  };
  std::vector<double> typical(x->num_markers(), -1.0);  // Per marker, computed when first needed.
  // Frames to cut on one side: edge(k) is the slope difference at the edge after k cuts,
  // can_cut(k) whether the k-th sample from the gap may go.
  auto frames_to_cut = [&](int m, const std::function<double(int)>& edge, const std::function<bool(int)>& can_cut) {
    if (typical[m] < 0.0) typical[m] = TypicalSlopeDifference(*x, reference, m);
    const double good = kTrimTypicalFactor * typical[m];
    int best = 0;
    double best_difference = edge(0);
    if (best_difference <= good) return 0;
    for (int k = 1; k <= trim_max && can_cut(k); ++k) {
      const double d = edge(k);
      if (d <= good) return k;
      if (d < best_difference) best_difference = d, best = k;
    }
    return best;
  };
  int trimmed = 0;
  for (const Gap& gap : FindGaps(*x)) {
    const int m = gap.marker;
    bool natural = false;
    for (int f = gap.first; f <= gap.last && !natural; ++f) natural = !unflagged.valid(f, m);
    if (!natural) continue;
    if (gap.first > 0) {
      const int best = frames_to_cut(
          m, [&](int k) { return SlopeDifference(*x, reference, m, gap.first - 1 - k); },
          [&](int k) { return gap.first - 1 - k >= 0 && x->valid(gap.first - 1 - k, m) && trimmable(gap.first - k, m); });
      for (int k = 0; k < best; ++k) x->SetMissing(gap.first - 1 - k, m);
      trimmed += best;
    }
    if (gap.last + 1 < x->num_frames()) {
      const int best = frames_to_cut(
          m, [&](int k) { return SlopeDifference(*x, reference, m, gap.last + 2 + k); },
          [&](int k) {
            return gap.last + 1 + k < x->num_frames() && x->valid(gap.last + 1 + k, m) && trimmable(gap.last + k, m);
          });
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
// The samples of frame f of the problem solved again (NaN = missing), into *samples
// (sized #M); called from both halves' threads at once, so it only reads. Read frame by
// frame, so that a whole-take copy of trajectories as observations (1 KB per frame) is
// not needed.
using FrameSamples = std::function<void(size_t f, std::vector<Eigen::Vector3d>* samples)>;

// The earlier solution a re-solve starts from and rejoins: a Motion, or a CompactMotion
// (kinematics/compact_motion.h) read frame by frame, so that a long take's reference and
// naive solves need not be held whole in double between their uses.
class EarlierSolution {
 public:
  EarlierSolution(const Motion& motion) : motion_(&motion) {}           // NOLINT: implicit.
  EarlierSolution(const CompactMotion& motion) : compact_(&motion) {}   // NOLINT: implicit.
  void Frame(size_t f, Pose* pose) const {
    if (motion_ != nullptr) {
      *pose = motion_->frames[f];
    } else {
      compact_->Frame(static_cast<int>(f), pose);
    }
  }
  Motion Whole() const { return motion_ != nullptr ? *motion_ : compact_->ToMotion(); }

 private:
  const Motion* motion_ = nullptr;
  const CompactMotion* compact_ = nullptr;
};

int ResolveChangedRange(const Skeleton& skeleton, const MarkerSet& markers, const Observations& observed,
                        const FrameSamples& repaired, const EarlierSolution& naive, const MarkerSolveOptions& options,
                        double tolerance, size_t begin, size_t end, Motion* motion) {
  int resolved = 0;
  MarkerFrameSolver solver(skeleton, markers, options);
  FkData fk(skeleton), fk_naive(skeleton);
  std::vector<Eigen::Vector3d> samples(markers.num_markers());
  Pose earlier;
  bool in_sync = true;
  for (size_t f = begin; f < end; ++f) {
    repaired(f, &samples);
    bool changed = false;
    for (int m = 0; m < markers.num_markers() && !changed; ++m) {
      changed = !SameSample(samples[m], observed[f][m]);
    }
    if (!changed && in_sync) continue;
    // The previous pose; at the start of a range, naive's (the other range may be
    // writing the frame before it).
    Pose pose;
    if (f > begin) {
      pose = motion->frames[f - 1];
    } else {
      naive.Frame(begin > 0 ? begin - 1 : 0, &pose);
    }
    FrameSolveReport frame;
    if (solver.Solve(samples, &pose, &frame).ok()) motion->frames[f] = pose;
    ++resolved;
    in_sync = false;
    if (!changed) {
      ForwardKinematics(skeleton, motion->frames[f], &fk);
      naive.Frame(f, &earlier);
      ForwardKinematics(skeleton, earlier, &fk_naive);
      double difference = 0.0;
      for (int j = 0; j < skeleton.num_joints(); ++j) {
        difference = std::max(difference, (fk.world_positions[j] - fk_naive.world_positions[j]).norm());
      }
      in_sync = difference <= tolerance;
      if (in_sync) motion->frames[f] = earlier;
    }
  }
  return resolved;
}

// The clip is solved in two halves, the second starting from naive's pose before its
// first frame, as if the frames before it had rejoined naive; with `parallel` the halves
// run on two threads. The halves are the same either way, so the result does not depend
// on the thread count (a batch runs its takes single-threaded side by side).
Status ResolveChangedFrames(const Skeleton& skeleton, const MarkerSet& markers, const Observations& observed,
                            const FrameSamples& repaired, const EarlierSolution& naive,
                            const MarkerSolveOptions& options, double tolerance, bool parallel, Motion* motion,
                            int* resolved) {
  *motion = naive.Whole();
  const size_t n = observed.size(), half = n >= 64 ? n / 2 : n;
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

// The same with the repaired samples as observations, or as trajectories read frame by
// frame (the samples TrajectoryObservations would give, without its copy).
Status ResolveChangedFrames(const Skeleton& skeleton, const MarkerSet& markers, const Observations& observed,
                            const Observations& repaired, const EarlierSolution& naive,
                            const MarkerSolveOptions& options, double tolerance, bool parallel, Motion* motion,
                            int* resolved) {
  const FrameSamples samples = [&](size_t f, std::vector<Eigen::Vector3d>* out) { *out = repaired[f]; };
  return ResolveChangedFrames(skeleton, markers, observed, samples, naive, options, tolerance, parallel, motion,
                              resolved);
}

// Frame f of trajectories as observations (NaN = missing), into *out (sized #M).
void TrajectoryFrame(const MarkerTrajectories& trajectories, int f, std::vector<Eigen::Vector3d>* out) {
  for (int m = 0; m < trajectories.num_markers(); ++m) (*out)[m] = trajectories.position(f, m);
}

Status ResolveChangedFrames(const Skeleton& skeleton, const MarkerSet& markers, const Observations& observed,
                            const MarkerTrajectories& repaired, const EarlierSolution& naive,
                            const MarkerSolveOptions& options, double tolerance, bool parallel, Motion* motion,
                            int* resolved) {
  const FrameSamples samples = [&](size_t f, std::vector<Eigen::Vector3d>* out) {
    TrajectoryFrame(repaired, static_cast<int>(f), out);
  };
  return ResolveChangedFrames(skeleton, markers, observed, samples, naive, options, tolerance, parallel, motion,
                              resolved);
}

// Frames on each side of a carried run its edge velocities are measured over.
constexpr int kCarryVelocityFrames = 2;

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

// ObservationTrajectories(markers, ReconstructMarkers(skeleton, markers, motion)), the same
// samples, without the intermediate observations (1 KB per frame of a long take).
MarkerTrajectories ReconstructedPaths(const Skeleton& skeleton, const MarkerSet& markers, const Motion& motion) {
  std::vector<std::string> labels;
  for (int m = 0; m < markers.num_markers(); ++m) labels.push_back(markers.label(m));
  MarkerTrajectories out(labels, static_cast<int>(motion.frames.size()));
  FkData fk(skeleton);
  for (size_t f = 0; f < motion.frames.size(); ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    for (int m = 0; m < markers.num_markers(); ++m) {
      const Eigen::Vector3d position = markers.Position(m, fk);
      if (position.allFinite()) out.SetSample(static_cast<int>(f), m, position);
    }
  }
  return out;
}

// What every step of the repair reads: the model, the take, the options, and the defaults
// the options select.
struct RepairContext {
  const Skeleton& skeleton;
  const MarkerSet& markers;
  const Observations& observed;
  const RepairOptions& options;
  double outlier;            // The fixed gate and the robust gates' cap: outlier_distance, else dp_max.
  double resync_tolerance;   // Re-solves of changed frames stop where the solution rejoins the earlier one.
  ResidualModelOptions model_options;  // Step 3b (and its refit after relabelling).
  bool keep_reconstructed;   // X^ also as observations (Reference::reconstructed), for the intermediates.
};

// The context of one repair, its defaults resolved once for every step.
RepairContext MakeRepairContext(const Skeleton& skeleton, const MarkerSet& markers, const Observations& observed,
                                const RepairOptions& options, bool keep_reconstructed) {
  const double outlier = options.outlier_distance > 0.0 ? options.outlier_distance : options.dp_max;
  ResidualModelOptions model_options;
  model_options.robust = options.robust_outliers;
  model_options.mads = options.outlier_mads;
  model_options.min_distance = options.outlier_min_distance > 0.0 ? options.outlier_min_distance : outlier / 4.0;
  model_options.max_distance = outlier;
  model_options.fixed_distance = outlier;
  const double resync_tolerance = options.resync_tolerance > 0.0 ? options.resync_tolerance : options.dp_max * 1e-3;
  return {skeleton, markers, observed, options, outlier, resync_tolerance, model_options, keep_reconstructed};
}

// The reference Y^ and the marker paths it predicts, X^, as trajectories (and as
// observations only for the intermediates: the same samples, 1 KB per frame of a long take).
// After gap detection Y^ is read only by its refit, frame by frame: it is then kept
// compact (`kept`, float: kinematics/compact_motion.h) and `motion` freed.
struct Reference {
  Motion motion;
  CompactMotion kept;
  Observations reconstructed;
  MarkerTrajectories paths;
};

// A stage's per-frame data freed as soon as no later stage reads it (a long take holds
// a dozen such arrays of one to two KB per frame).
template <typename T>
void Release(T* value) {
  *value = T();
}

// Step 3: X^ from Y^ (again whenever Y^ is redone).
void ReconstructReference(const RepairContext& ctx, Reference* reference) {
  if (ctx.keep_reconstructed) {
    reference->reconstructed = ReconstructMarkers(ctx.skeleton, ctx.markers, reference->motion);
    reference->paths = ObservationTrajectories(ctx.markers, reference->reconstructed);
  } else {
    reference->paths = ReconstructedPaths(ctx.skeleton, ctx.markers, reference->motion);
  }
}

// Error unless the options are valid, the observations fit the marker set, and the
// unlabelled points (if any) have the observations' frames and their tracks' width.
Status CheckRepairInputs(const MarkerSet& markers, const Observations& observed, const UnlabelledPoints& unlabelled,
                         const RepairOptions& options) {
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
  return Status::Ok();
}

// The first frame's warm start of the sequence solves (RepairOptions::start_pose).
Pose StartPose(const RepairContext& ctx) {
  const Pose& start = ctx.options.start_pose;
  return start.rotations.empty() ? RestPose(ctx.skeleton) : start;
}

// Steps 1 and 2 with the robust tracker: it needs no naive solve, so with `parallel` the
// two run side by side on two threads.
Status SolveNaiveBesideTracker(const RepairContext& ctx, const std::function<void(int)>& naive_progress,
                               StageClock* clock, Motion* naive, Motion* reference, SequenceSolveReport* sequence) {
  const RepairOptions& options = ctx.options;
  Status reference_status = Status::Ok();
  SequenceSolveReport tracker_report;
  auto track = [&] {
    reference_status = SolveSequence(ctx.skeleton, ctx.markers, ctx.observed, options.tracker,
                                     StartPose(ctx), reference, &tracker_report);
  };
  std::thread tracker;
  if (options.parallel) tracker = std::thread(track);
  const Status status = SolveSequence(ctx.skeleton, ctx.markers, ctx.observed, options.naive, StartPose(ctx),
                                      naive, sequence, naive_progress);
  if (options.parallel) {
    tracker.join();
  } else {
    track();
  }
  if (!status.ok()) return status;
  if (!reference_status.ok()) return reference_status;
  clock->Lap(options.parallel ? "IK (naive) + reference (robust tracker), in parallel"
                              : "IK (naive) + reference (robust tracker)");
  return Status::Ok();
}

// Steps 1 and 2 with the whole-clip reference: the robust clip solve starts from Y.
Status SolveNaiveThenClip(const RepairContext& ctx, const std::function<void(int)>& naive_progress,
                          StageClock* clock, Motion* naive, Motion* reference, SequenceSolveReport* sequence) {
  Status status = SolveSequence(ctx.skeleton, ctx.markers, ctx.observed, ctx.options.naive, StartPose(ctx),
                                naive, sequence, naive_progress);
  if (!status.ok()) return status;
  clock->Lap("IK (naive solve)");
  *reference = *naive;
  ClipSolveReport clip;
  status = SolveClip(ctx.skeleton, ctx.markers, ctx.observed, ctx.options.reference, reference, &clip);
  if (!status.ok()) return status;
  clock->Lap("Reference solve (robust clip)");
  return Status::Ok();
}

// Step 3c: swapped samples relabelled in *x (*relabelled: *x's observations, when any).
// The robust tracker leans toward the swapped labels while a swap lasts (on a bone that
// one marker pins, such as the thumb's, it follows them), so the relabelled samples would
// be judged outliers against it: it is redone where the samples changed, until it rejoins
// the earlier solution, and X^ with it. A swap from the first frame misled the tracker's
// start (its orientation search): then the whole tracker is run again.
Status UndoSwapsStep(const RepairContext& ctx, const MarkerResidualModel& model, MarkerTrajectories* x,
                     Observations* relabelled, Reference* reference, RepairReport* report) {
  const RepairOptions& options = ctx.options;
  SwapDetectionOptions swap_options;
  swap_options.radius = options.swap_radius > 0.0 ? options.swap_radius : 3.0 * options.dp_max;
  swap_options.min_frames = options.swap_min_frames;
  report->swaps = UndoSwaps(model, swap_options, x);
  if (report->swaps.empty()) return Status::Ok();
  *relabelled = TrajectoryObservations(*x);
  if (options.reference_kind != ReferenceKind::kTracker) return Status::Ok();
  Motion redone;
  Status status = Status::Ok();
  if (report->swaps.front().first == 0) {
    SequenceSolveReport tracker_report;
    status = SolveSequence(ctx.skeleton, ctx.markers, *relabelled, options.tracker, StartPose(ctx), &redone,
                           &tracker_report);
  } else {
    int resolved = 0;
    status = ResolveChangedFrames(ctx.skeleton, ctx.markers, ctx.observed, *relabelled, reference->motion,
                                  options.tracker, ctx.resync_tolerance, options.parallel, &redone, &resolved);
  }
  if (!status.ok()) return status;
  reference->motion = std::move(redone);
  ReconstructReference(ctx, reference);
  return Status::Ok();
}

// Step 3d: the take's unlabelled points become the samples of missing markers in *x where
// the residual model's prediction and the marker's track say they belong.
void AssignUnlabelledStep(const RepairContext& ctx, const MarkerResidualModel& model,
                          const UnlabelledPoints& unlabelled, MarkerTrajectories* x, Observations* relabelled,
                          RepairReport* report) {
  const RepairOptions& options = ctx.options;
  UnlabelledAssignmentOptions assign;
  assign.mads = options.outlier_mads;
  assign.min_distance = options.unlabelled_min_distance > 0.0 ? options.unlabelled_min_distance : ctx.outlier / 2.0;
  assign.max_distance = options.unlabelled_max_distance > 0.0 ? options.unlabelled_max_distance : 1.25 * ctx.outlier;
  assign.min_frames = options.unlabelled_min_frames;
  report->unlabelled = AssignUnlabelledPoints(model, unlabelled, assign, x);
  if (!report->unlabelled.empty()) *relabelled = TrajectoryObservations(*x);
}

// After relabelling, the naive solve redone where the samples changed, and the residual
// model refitted: it was fitted with the swapped samples in its window and without the
// assigned ones.
Status ResolveRelabelled(const RepairContext& ctx, const Observations& relabelled, const Reference& reference,
                         const MarkerTrajectories& x, const RepairReport& report, CompactMotion* naive,
                         MarkerResidualModel* model) {
  Motion solved;
  int resolved = 0;
  const Status status = ResolveChangedFrames(ctx.skeleton, ctx.markers, ctx.observed, relabelled, *naive,
                                             ctx.options.naive, ctx.resync_tolerance, ctx.options.parallel, &solved,
                                             &resolved);
  if (!status.ok()) return status;
  *naive = CompactMotion(solved);
  Release(&solved);
  *model = FitMarkerResidualModel(ctx.skeleton, ctx.markers, reference.motion, reference.paths, x,
                                  ctx.model_options);
  // The reference followed the swapped labels: its parent frames do not judge the
  // relabelled samples (marker_residual_model.h).
  for (const MarkerSwap& swap : report.swaps) {
    for (int f = swap.first; f <= swap.last; ++f) {
      for (const auto& [from, to] : swap.from_to) model->absorbed[f][to] = 0;
    }
  }
  return Status::Ok();
}

// Steps 3c and 3d, then the naive solve redone where the samples changed; steps 4-7 work
// on the relabelled samples (*relabelled, when any changed).
Status RelabelSamples(const RepairContext& ctx, const UnlabelledPoints& unlabelled, StageClock* clock,
                      CompactMotion* naive, Reference* reference, MarkerResidualModel* model, MarkerTrajectories* x,
                      Observations* relabelled, RepairReport* report) {
  const RepairOptions& options = ctx.options;
  const bool assigning = options.assign_unlabelled && unlabelled.num_tracks() > 0;
  if (options.undo_swaps) {
    const Status status = UndoSwapsStep(ctx, *model, x, relabelled, reference, report);
    if (!status.ok()) return status;
    if (assigning) clock->Lap("Swap Detection");
  }
  if (assigning) AssignUnlabelledStep(ctx, *model, unlabelled, x, relabelled, report);
  if (!report->swaps.empty() || !report->unlabelled.empty()) {
    const Status status = ResolveRelabelled(ctx, *relabelled, *reference, *x, *report, naive, model);
    if (!status.ok()) return status;
  }
  if (assigning) {
    clock->Lap("Unlabelled Assignment");  // With the re-solve of the changed frames.
  } else if (options.undo_swaps) {
    clock->Lap("Swap Detection");
  }
  return Status::Ok();
}

// Step 4's intervals the input itself marks: the capture's gaps, the labels that received
// swapped samples, and the runs assigned unlabelled points.
void RecordInputIntervals(const MarkerTrajectories& captured, RepairReport* report) {
  for (const Gap& gap : FindGaps(captured)) report->detected.push_back({gap.marker, gap.first, gap.last, "missing"});
  for (const MarkerSwap& swap : report->swaps) {
    for (const auto& [from, to] : swap.from_to) {
      report->detected.push_back({to, swap.first, swap.last, "swap"});
    }
  }
  for (const UnlabelledAssignment& a : report->unlabelled) {
    report->detected.push_back({a.marker, a.first, a.last, "unlabelled"});
  }
}

// DetectBad(Y, Y^) as marker samples (frames x markers): a joint difference condemns a
// marker only where it moves the marker past its gate.
Status JointDifferenceSamples(const RepairContext& ctx, const CompactMotion& naive, const Reference& reference,
                              const MarkerResidualModel& model, const MarkerTrajectories& x,
                              std::vector<std::vector<char>>* bad) {
  std::vector<std::vector<char>> bad_joints;
  const Status status = DetectBadJoints(ctx.skeleton, naive, reference.motion,
                                        {ctx.options.dp_max, ctx.options.dr_max_rad}, &bad_joints);
  if (!status.ok()) return status;
  *bad = BadMarkerSamples(ctx.markers, bad_joints);
  FkData fk_naive(ctx.skeleton);
  Pose pose;
  for (int f = 0; f < x.num_frames(); ++f) {
    bool any = false;
    for (int m = 0; m < x.num_markers() && !any; ++m) any = (*bad)[f][m];
    if (!any) continue;
    naive.Frame(f, &pose);
    ForwardKinematics(ctx.skeleton, pose, &fk_naive);
    for (int m = 0; m < x.num_markers(); ++m) {
      if ((*bad)[f][m] && (ctx.markers.Position(m, fk_naive) - reference.paths.position(f, m)).norm() <= model.gate[m]) {
        (*bad)[f][m] = 0;
      }
    }
  }
  return Status::Ok();
}

// Names each new gap of `flagged` by its first cause: swap (a label left without a
// sample), outlier, else joint difference; gaps the capture had are already recorded.
// outlier: 1 for each sample (x.index) of x that the outlier test removed.
void RecordNewGaps(const MarkerTrajectories& flagged, const MarkerTrajectories& captured,
                   const MarkerTrajectories& x, const std::vector<char>& outlier, RepairReport* report) {
  for (const Gap& gap : FindGaps(flagged)) {
    bool natural = true, outlying = false, swapped = false;
    for (int f = gap.first; f <= gap.last; ++f) {
      natural &= !captured.valid(f, gap.marker);
      swapped |= captured.valid(f, gap.marker) && !x.valid(f, gap.marker);
      outlying |= outlier[x.index(f, gap.marker)] != 0;
    }
    if (!natural) {
      report->detected.push_back(
          {gap.marker, gap.first, gap.last, swapped ? "swap" : outlying ? "outlier" : "joint difference"});
    }
  }
}

// Step 4: *flagged is x without its outliers (samples past their marker's gate) and the
// samples the joint difference condemns (`bad`, JointDifferenceSamples); every interval
// found goes into the report. The outliers are kept as a mask, not as a third copy of
// the take's samples (1.2 KB per frame of a long take).
void DetectGaps(const MarkerResidualModel& model, const MarkerTrajectories& captured, const MarkerTrajectories& x,
                const std::vector<std::vector<char>>& bad, RepairReport* report, MarkerTrajectories* flagged) {
  RecordInputIntervals(captured, report);
  *flagged = x.SharingSamples();  // Its own mask over x's samples.
  std::vector<char> outlier(static_cast<size_t>(x.num_frames()) * x.num_markers(), 0);
  for (int f = 0; f < x.num_frames(); ++f) {
    for (int m = 0; m < x.num_markers(); ++m) {
      if (x.valid(f, m) && model.Outlying(f, m, x.position(f, m))) {
        outlier[x.index(f, m)] = 1;
        flagged->SetMissing(f, m);
      }
    }
  }
  // A sample the swap step gave to its label was chosen there by the kinematic fit of both
  // assignments: the joint difference, which condemns every marker its joint moves past
  // the gate, does not undo that choice (on the synthetic walk of scripts/synthetic_walk.py
  // it cut a wrist marker's 57 relabelled samples); the outlier test above still applies.
  std::vector<std::vector<char>> swapped(x.num_frames(), std::vector<char>(x.num_markers(), 0));
  for (const MarkerSwap& swap : report->swaps) {
    for (int f = swap.first; f <= swap.last; ++f) {
      for (const auto& [from, to] : swap.from_to) swapped[f][to] = x.valid(f, to);
    }
  }
  for (int f = 0; f < x.num_frames(); ++f) {
    for (int m = 0; m < x.num_markers(); ++m) {
      if (bad[f][m] && !swapped[f][m] && flagged->valid(f, m)) flagged->SetMissing(f, m);
    }
  }
  RecordNewGaps(*flagged, captured, x, outlier, report);
}

// Step 5, in the thesis' order: smart trimming, small-track removal, small-gap filling.
// *before_small keeps the samples before the small gaps' cubics: step 6 conditions on them.
void PreprocessGaps(const RepairContext& ctx, const MarkerTrajectories& reference_paths,
                    const MarkerTrajectories& unflagged, const MarkerTrajectories& captured,
                    MarkerTrajectories* x, MarkerTrajectories* before_small, RepairReport* report) {
  report->trimmed_samples = TrimAroundGaps(reference_paths, ctx.options.trim_max, unflagged, captured, x);
  // A track holding relabelled samples (a swap's, judged against the label's prediction)
  // is not too short to trust.
  const auto relabelled = [&](int f, int m) {
    return x->valid(f, m) && !(captured.valid(f, m) && x->position(f, m) == captured.position(f, m));
  };
  report->removed_track_samples = RemoveSmallTracks(ctx.options.small_track, relabelled, x);
  *before_small = x->SharingSamples();  // x's samples until the small gaps' fill writes into x.
  report->polynomial_samples = FillSmallGaps(ctx.options.small_gap, x);
  for (const Gap& gap : FindGaps(*before_small)) {
    if (x->valid(gap.first, gap.marker)) report->filled.push_back({gap.marker, gap.first, gap.last, "polynomial"});
  }
}

// Step 6 with the tracker: Y^ refitted without the cut samples where they were (the
// trimmed samples kept), until it rejoins.
Status RefitReference(const RepairContext& ctx, const Observations& input, const MarkerTrajectories& flagged,
                      const CompactMotion& reference, Motion* refitted) {
  int resolved = 0;
  return ResolveChangedFrames(ctx.skeleton, ctx.markers, input, flagged, reference,
                              ctx.options.tracker, ctx.resync_tolerance, ctx.options.parallel, refitted, &resolved);
}

// The frames beside each carried run (up to `frames` a side: the kriging's conditioning
// samples) solved again without the markers that the run hides on the joint's parent bone
// and below, so that their reconstruction is the one the gap gets: the fill's offsets from
// X^ taken there then carry how far the subject puts those markers from where the
// remaining markers place the body. (CMU 02_05 on the subject calibrated on 02_01: with
// its ankle marker hidden, the shank solved from the knee and shin markers puts the ankle
// 40-60 mm off, and the fill jumped by that much at the gap's edge.)
void ResolveGapEdges(const RepairContext& ctx, const MarkerTrajectories& flagged,
                     const std::vector<CarriedJointRun>& runs, int frames, MarkerFrameSolver* solver, Motion* motion) {
  const int total = motion->num_frames();
  std::vector<std::vector<char>> hide(total, std::vector<char>(flagged.num_markers(), 0));
  for (const CarriedJointRun& run : runs) {
    for (int side = 0; side < 2; ++side) {
      const int inside = side == 0 ? run.first : run.last, step = side == 0 ? -1 : 1;
      for (int k = 1; k <= frames; ++k) {
        const int f = inside + step * k;
        if (f < 0 || f >= total) break;
        const int parent = std::max(ctx.skeleton.parent(run.joint), 0);
        for (int m = 0; m < flagged.num_markers(); ++m) {
          const int bone = ctx.markers.marker(m).attachments.front().joint;
          const bool near = ctx.skeleton.IsAncestorOrSelf(parent, bone);
          if (near && !flagged.valid(inside, m) && flagged.valid(f, m)) hide[f][m] = 1;
        }
      }
    }
  }
  for (int f = 0; f < total; ++f) {
    std::vector<Eigen::Vector3d> kept(flagged.num_markers());
    bool any = false;
    for (int m = 0; m < flagged.num_markers(); ++m) {
      any |= hide[f][m];
      kept[m] = hide[f][m] ? Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()) : flagged.position(f, m);
    }
    if (!any) continue;
    Pose pose = motion->frames[f];
    FrameSolveReport frame;
    if (solver->Solve(kept, &pose, &frame).ok()) motion->frames[f] = pose;
  }
}

// Step 6, carry_joints: the joints that the kept samples leave unobserved carried across
// their runs (signal/joint_gap_carry.h) in *motion; then each frame of a run solved again
// with the reference's options on the kept samples, warm-started from and pulled toward the
// carried pose, so that the joints the markers still see follow them and the others stay
// on the carried path. The runs go into the report. True if there were any.
bool CarryUnobservedJoints(const RepairContext& ctx, const MarkerTrajectories& flagged, Motion* motion,
                           RepairReport* report) {
  if (!ctx.options.carry_joints) return false;
  const std::vector<CarriedJointRun> runs = FindUnobservedJointRuns(ctx.skeleton, ctx.markers, flagged);
  if (runs.empty()) return false;
  const JointTemplateOptions templates;
  CarryJoints(ctx.skeleton, runs, kCarryVelocityFrames, &templates, motion);
  std::vector<char> carried(motion->num_frames(), 0);
  for (const CarriedJointRun& run : runs) std::fill(carried.begin() + run.first, carried.begin() + run.last + 1, 1);
  std::vector<Eigen::Vector3d> kept(flagged.num_markers());  // Frame by frame, not a copy of the take.
  MarkerFrameSolver solver(ctx.skeleton, ctx.markers, ctx.options.tracker);
  for (int f = 0; f < motion->num_frames(); ++f) {
    if (!carried[f]) continue;
    TrajectoryFrame(flagged, f, &kept);
    Pose pose = motion->frames[f];
    FrameSolveReport frame;
    if (solver.Solve(kept, &pose, &frame).ok()) motion->frames[f] = pose;
  }
  ResolveGapEdges(ctx, flagged, runs, ctx.options.fill_samples, &solver, motion);
  report->carried = runs;
  return true;
}

// Which cut runs are rough (noise, jitter): the removed samples' median |second
// difference| over refit_rough_factor times the marker's own over its kept samples. None
// without a refitted reference (then every gap is filled from X^ as solved).
class RoughRuns {
 public:
  RoughRuns(bool refit, double factor, const MarkerTrajectories& before_small, const MarkerTrajectories& unflagged)
      : refit_(refit), factor_(factor), unflagged_(unflagged), own_(before_small.num_markers(), -1.0) {
    if (!refit) return;
    for (int m = 0; m < before_small.num_markers(); ++m) {
      own_[m] = MedianSecondDifference(before_small, nullptr, m, 0, before_small.num_frames() - 1);
    }
  }
  bool IsRough(const Gap& gap) const {
    const double roughness = MedianSecondDifference(unflagged_, nullptr, gap.marker, gap.first, gap.last);
    return refit_ && roughness >= 0.0 && roughness > factor_ * own_[gap.marker];
  }

 private:
  bool refit_;
  double factor_;
  const MarkerTrajectories& unflagged_;
  std::vector<double> own_;  // Per marker; -1 without refit.
};

// A rough run is cut whole: the samples beside it as rough as it (a noise run's ends and
// small draws pass the gates), judged on the residual to X^ as solved
// (signal/rough_run_extension.h); they leave the kriging's conditioning samples too.
// Returns the samples cut.
int ExtendRoughRuns(const RepairContext& ctx, const RoughRuns& rough, const MarkerTrajectories& unflagged,
                    const MarkerTrajectories& reference_paths, MarkerTrajectories* x,
                    MarkerTrajectories* before_small) {
  // The threshold is at least a tenth of the gates' floor (1 mm by default): a noise-free
  // marker's median is ~0, and the walk then cut the clean samples where X^ leaned toward
  // the run (the synthetic demo walk: 4-7 a side; on real takes the floor changes nothing).
  const double threshold_floor = 0.1 * ctx.model_options.min_distance;
  std::vector<double> own(x->num_markers(), std::numeric_limits<double>::quiet_NaN());  // Computed once needed.
  int cut = 0;
  for (const Gap& gap : FindGaps(*x)) {
    if (!rough.IsRough(gap)) continue;
    double& own_level = own[gap.marker];
    if (std::isnan(own_level)) {
      own_level = MedianSecondDifference(*before_small, &reference_paths, gap.marker, 0, x->num_frames() - 1);
    }
    if (own_level < 0.0) continue;
    const double threshold = std::max(ctx.options.rough_extension_factor * own_level, threshold_floor);
    cut += ExtendRoughRun(gap, unflagged, reference_paths, threshold, ctx.options.trim_max, x, before_small);
  }
  return cut;
}

// Each remaining gap refilled: X^ (refitted for smooth runs and gaps, as solved for rough
// runs) plus the offset kriged from the samples that survived detection and preprocessing
// (not the small gaps' cubics nor another gap's fill; one offset process per reference),
// or Algorithm 3's blend where no process was estimated.
Status FillGaps(const RepairContext& ctx, const RoughRuns& rough, bool refit, const MarkerTrajectories& reference_paths,
                const MarkerTrajectories& refit_paths, const MarkerTrajectories& before_small, MarkerTrajectories* x,
                RepairReport* report) {
  const RepairOptions& options = ctx.options;
  GapFillOptions fill;
  if (options.velocity_clamp > 0.0) fill.velocity_clamp = options.velocity_clamp;
  fill.edge_samples = options.edge_samples;
  OffsetKrigingOptions kriging;
  kriging.samples_per_side = options.fill_samples;
  std::vector<OffsetProcess> processes, refit_processes;
  Status status = Status::Ok();
  if (options.fill == GapFillKind::kKriging) {
    status = EstimateOffsetProcesses(before_small, reference_paths, kriging, &processes);
    if (status.ok() && refit) status = EstimateOffsetProcesses(before_small, refit_paths, kriging, &refit_processes);
    if (!status.ok()) return status;
  }
  for (const Gap& gap : FindGaps(*x)) {
    const bool from_refit = refit && !rough.IsRough(gap);
    const MarkerTrajectories& paths = from_refit ? refit_paths : reference_paths;
    const std::vector<OffsetProcess>& offsets = from_refit ? refit_processes : processes;
    if (options.fill == GapFillKind::kKriging && offsets[gap.marker].valid) {
      status = FillGapByKriging(gap, before_small, paths, offsets[gap.marker], kriging, x);
    } else {
      status = FillGapFromReference(gap, paths, fill, x);
    }
    if (!status.ok()) return status;
    const bool whole = gap.first == 0 && gap.last + 1 == x->num_frames();
    report->filled.push_back({gap.marker, gap.first, gap.last, whole ? "reference only" : "reference"});
  }
  return Status::Ok();
}

// Step 6, marker filling from the reference. The tracker leaned toward the samples now cut
// (its loss bounds the pull of each sample, not of a displaced run of them): it is refitted
// without them. A smooth run (a marker flown off, a ghost) and a gap without samples are
// filled from the refitted X^; a rough run, whose samples scatter about the true path so
// that the robust solve averaged them, from X^ as solved (issue 16, BENCHMARKS.md).
// With release_motion, Y^ itself (reference.kept) is freed once the refit has read it
// (nothing after it does; 0.5 KB per frame of a long take while X^ is refitted).
Status FillMarkers(const RepairContext& ctx, const Observations& input, Reference* reference_in,
                   bool release_motion, const MarkerTrajectories& flagged, const MarkerTrajectories& unflagged,
                   MarkerTrajectories* before_small, MarkerTrajectories* x, RepairReport* report) {
  const Reference& reference = *reference_in;
  const RepairOptions& options = ctx.options;
  MarkerTrajectories refit_paths;
  const bool refit = options.refit_reference && options.reference_kind == ReferenceKind::kTracker;
  if (refit) {
    Motion refitted;
    const Status status = RefitReference(ctx, input, flagged, reference.kept, &refitted);
    if (!status.ok()) return status;
    if (release_motion) Release(&reference_in->kept);
    CarryUnobservedJoints(ctx, flagged, &refitted, report);
    refit_paths = ReconstructedPaths(ctx.skeleton, ctx.markers, refitted);
  }
  const RoughRuns rough(refit, options.refit_rough_factor, *before_small, unflagged);
  if (refit && options.rough_extension_factor > 0.0) {
    report->rough_extension_samples += ExtendRoughRuns(ctx, rough, unflagged, reference.paths, x, before_small);
  }
  if (!refit) {  // Gaps are filled from X^ as solved: carry its unobserved joints first.
    Motion carried = reference.kept.ToMotion();
    if (CarryUnobservedJoints(ctx, flagged, &carried, report)) {
      const MarkerTrajectories carried_paths = ReconstructedPaths(ctx.skeleton, ctx.markers, carried);
      return FillGaps(ctx, rough, refit, carried_paths, refit_paths, *before_small, x, report);
    }
  }
  return FillGaps(ctx, rough, refit, reference.paths, refit_paths, *before_small, x, report);
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
  if (Status status = CheckRepairInputs(markers, observed, unlabelled, options); !status.ok()) return status;
  *report = RepairReport();
  StageClock clock(report);
  const RepairContext ctx = MakeRepairContext(skeleton, markers, observed, options, intermediates != nullptr);
  // 1. Naive solve and 2. robust reference.
  Motion naive;
  Reference reference;
  SequenceSolveReport sequence;
  const int num_frames = static_cast<int>(observed.size());
  std::function<void(int)> naive_progress;
  if (progress) {
    naive_progress = [&](int done) {
      progress(options.reference_kind == ReferenceKind::kTracker ? "IK + reference" : "IK", done, num_frames);
    };
  }
  Status status = options.reference_kind == ReferenceKind::kTracker
                      ? SolveNaiveBesideTracker(ctx, naive_progress, &clock, &naive, &reference.motion, &sequence)
                      : SolveNaiveThenClip(ctx, naive_progress, &clock, &naive, &reference.motion, &sequence);
  if (!status.ok()) return status;
  report->naive_rms = RmsOver(skeleton, markers, naive, observed);
  report->naive_unconverged_frames = sequence.unconverged_frames;
  report->naive_held_frames = sequence.held_frames;
  report->naive_twist_held_frames = sequence.twist_held_frames;
  // From here Y is read only frame by frame (gap detection, the re-solves from it): kept
  // compact (float, kinematics/compact_motion.h: 0.5 instead of 1.8 KB per frame while the
  // residual model is fitted and the gaps are detected and filled). Its rounding (< 1e-7
  // relative) reaches the outputs only through those re-solves' starts and the frames
  // they copy, far inside 0.01 mm (BENCHMARKS.md).
  CompactMotion naive_kept(naive);
  Release(&naive);
  report->reference_rms = RmsOver(skeleton, markers, reference.motion, observed);
  // 3. Marker reconstruction.
  ReconstructReference(ctx, &reference);
  clock.Lap("Marker Reconstruction");
  // 3b. Residual model.
  MarkerTrajectories x = ObservationTrajectories(markers, observed);
  MarkerResidualModel model =
      FitMarkerResidualModel(skeleton, markers, reference.motion, reference.paths, x, ctx.model_options);
  clock.Lap("Residual Model");
  // 3c. Swaps: relabel; 3d. unlabelled points labelled; then redo the naive solve where
  // the samples changed.
  Observations relabelled;
  status = RelabelSamples(ctx, unlabelled, &clock, &naive_kept, &reference, &model, &x, &relabelled, report);
  if (!status.ok()) return status;
  // The samples as captured, x before relabelling: made again from the observations
  // rather than copied before it, so that the relabelling does not hold a third copy; x's
  // own samples when nothing was relabelled.
  const bool changed = !report->swaps.empty() || !report->unlabelled.empty();
  MarkerTrajectories captured = changed ? ObservationTrajectories(markers, observed) : x.SharingSamples();
  const Observations& input = changed ? relabelled : observed;
  // 4. Gap detection.
  std::vector<std::vector<char>> bad;
  status = JointDifferenceSamples(ctx, naive_kept, reference, model, x, &bad);
  if (!status.ok()) return status;
  // From here Y^ is read only by its refit (step 6), frame by frame: kept compact too.
  reference.kept = CompactMotion(reference.motion);
  Release(&reference.motion);
  MarkerTrajectories flagged;
  DetectGaps(model, captured, x, bad, report, &flagged);
  Release(&bad);
  // unflagged, flagged and x (until its small gaps are filled) share one array of samples,
  // each with its own mask (MarkerTrajectories::SharingSamples).
  MarkerTrajectories unflagged = std::move(x);
  x = flagged.SharingSamples();
  if (intermediates == nullptr) Release(&model);
  clock.Lap("Gap Detection");
  // 5. Preprocessing, in the thesis' order.
  MarkerTrajectories before_small;
  PreprocessGaps(ctx, reference.paths, unflagged, captured, &x, &before_small, report);
  Release(&captured);
  clock.Lap("Gap Preprocessing");
  // 6. Marker filling from the reference.
  status = FillMarkers(ctx, input, &reference, intermediates == nullptr, flagged, unflagged, &before_small, &x, report);
  if (!status.ok()) return status;
  // Every sample is now valid; those never marked bad are the input's, bit for bit.
  Release(&flagged);
  Release(&unflagged);
  Release(&before_small);
  *repaired = TrajectoryObservations(x);
  Release(&x);
  if (intermediates == nullptr) Release(&reference);  // The re-solve starts from the naive solve only.
  clock.Lap("Marker Filling");
  // 7. Re-solve.
  if (progress) progress("re-solve", 0, num_frames);
  status = ResolveChangedFrames(skeleton, markers, input, *repaired, naive_kept, options.naive,
                                ctx.resync_tolerance, options.parallel, motion, &report->resolved_frames);
  if (!status.ok()) return status;
  if (progress) progress("re-solve", num_frames, num_frames);
  report->repaired_rms = RmsOver(skeleton, markers, *motion, *repaired);
  clock.Lap("IK (re-solve)");
  if (intermediates != nullptr) {
    intermediates->naive = naive_kept.ToMotion();
    intermediates->reference = reference.kept.ToMotion();
    intermediates->reconstructed = std::move(reference.reconstructed);
    intermediates->residual_model = std::move(model);
  }
  return Status::Ok();
}

}  // namespace mocapsolve
