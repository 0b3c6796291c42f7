// Marker trajectory repair (thesis chapter 3, section 3.3): find broken intervals against
// a robust kinematic reference and refill them with Hermite-blended reference paths.
//
//   1. Naive solve Y: per-frame least squares (MarkerFrameSolver, warm-started).
//   2. Reference Y^: the thesis' robust neural solver is replaced, as section 3.3 allows,
//      by a robust kinematic solve: either the whole-clip solve with a robust loss and
//      smoothness (SolveClip, from Y), or the robust tracker: frame by frame with a
//      robust loss and a strong pull toward the previous frame (SolveSequence), which
//      needs no Y and so runs beside step 1 on a second thread, ~10x faster than the clip.
//   3. Marker reconstruction X^ = LBS(Y^, Z) (eq. 9, MarkerSet::Position).
//   3b. Residual model (marker_residual_model.h): per marker, the typical residual against
//      X^ (its median, in its joint's frame) and a robust gate (median + k MAD), or, with
//      `robust_outliers` false, chapter 3's fixed outlier_distance from X^.
//   3c. Swaps undone (swap_detection.h, `undo_swaps`): samples that fit another nearby
//      label's prediction far better than their own, or that exchange trajectories with
//      it, are relabelled; the naive solve is redone on the frames that changed, and so
//      is the tracker reference (which leans toward, or follows, swapped labels), with
//      X^ (the whole tracker when a swap touches the first frame). Steps 4-7 work on the
//      relabelled samples.
//   3d. Unlabelled points labelled (unlabelled_assignment.h, `assign_unlabelled`): points
//      the capture could not name (C3D "*52") become the samples of missing markers where
//      the prediction P of the residual model and continuity with the marker's track say
//      they belong, one to one per frame; the naive solve is redone on those frames too.
//   4. Gap detection: naturally missing samples; outliers, samples past their marker's
//      gate (the thesis takes these from its neural solver); and DetectBad(Y, Y^)
//      (Algorithm 2), which condemns a marker's sample only where the joint difference
//      moves that marker past its gate (a joint whose rotation no marker pins down, such
//      as a head carrying one marker, may differ between Y and Y^ without condemning it).
//   5. Gap preprocessing (3.3.4): smart trimming (cut up to trim_max frames on each side of
//      a gap, stopping at the first edge whose velocity difference between original and
//      reference is typical of the marker, else where it is smallest: the thesis' rule),
//      then small-track removal, then small-gap filling, in that order. Samples
//      relabelled in 3c/3d are neither trimmed nor dropped with a small track.
//   6. Marker filling: X^ plus the offset from it, kriged from the samples beside each gap
//      (signal/offset_kriging.h; or Algorithm 3's Hermite blend of the edge offsets). With
//      the tracker, X^ is first refitted without the cut samples where they were; runs
//      that were smooth (fly-off, ghost) and gaps are filled from the refitted X^, rough
//      runs (noise, jitter, which the robust solve averaged) from X^ as solved; a rough run
//      is first extended over the samples beside it that are as rough (a noise run's ends
//      and small draws pass the gates; signal/rough_run_extension.h). With carry_joints,
//      the joints whose observing markers are (nearly) all cut or missing (a hidden foot,
//      hand or head) are first carried across those frames in joint space, along the
//      joint's own motion elsewhere in the take where one matches (signal/joint_gap_template.h),
//      else a log-quaternion Hermite between the poses on both sides (signal/joint_gap_carry.h),
//      and those frames solved again with the reference's options pulled toward the carried
//      pose, so the joints the markers still see follow them; the fill_samples frames beside
//      each run are solved again without the markers the run hides, so that the offsets the
//      fill conditions on are taken against the same reconstruction; X^ comes from that motion.
//   7. Re-solve Y- on the filled markers: only the frames whose markers changed, and the
//      frames after each until the solution rejoins Y (within resync_tolerance), since
//      elsewhere the per-frame problem, its warm start and its prior are Y's own. With
//      `parallel`, the two halves of the clip on two threads (the second half starts
//      from Y's pose before it).
// Samples never marked bad are returned unchanged. Lengths are skeleton units
// (observations in the skeleton's frame, marker_observations.h).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_MARKER_REPAIR_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_MARKER_REPAIR_H_

#include <functional>
#include <string>
#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_repair/swap_detection.h"
#include "problems/marker_repair/unlabelled_assignment.h"
#include "problems/marker_solve/marker_clip_solver.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "signal/joint_gap_carry.h"

namespace mocapsolve {

enum class ReferenceKind { kClip, kTracker };

// Step 6's refill of a gap from X^: kBlend, X^ plus a Hermite blend of the edge offsets
// (thesis Algorithm 3, signal/gap_fill.h); kKriging, X^ plus the conditional mean of the
// offset modelled as mean + exponentially correlated process + white noise, estimated per
// marker from the take (signal/offset_kriging.h).
enum class GapFillKind { kBlend, kKriging };

struct RepairOptions {
  MarkerSolveOptions naive;        // Steps 1 and 7.
  ReferenceKind reference_kind = ReferenceKind::kClip;
  ClipSolveOptions reference;      // Step 2, kClip (give it a robust loss).
  MarkerSolveOptions tracker;      // Step 2, kTracker (a robust loss and a prior).
  bool parallel = true;            // Two threads: steps 1 and 2 (kTracker), step 7.
  double resync_tolerance = 0.0;   // Skeleton units (joint positions); <= 0: dp_max * 1e-3.
  double dp_max = 0.0;             // Joint position threshold, skeleton units.
  double dr_max_rad = 0.0;         // Joint rotation threshold.
  double outlier_distance = 0.0;   // Skeleton units; <= 0: dp_max. The fixed gate, and
                                   // the robust gates' cap.
  bool robust_outliers = true;     // Per-marker robust gates (marker_residual_model.h).
  double outlier_mads = 6.0;       // k of the robust gate.
  double outlier_min_distance = 0.0;  // Skeleton units: the robust gates' floor; <= 0:
                                      // outlier_distance / 4.
  bool undo_swaps = true;          // Step 3c.
  double swap_radius = 0.0;        // Skeleton units; <= 0: 3 dp_max.
  int swap_min_frames = 2;         // Frames a swap must persist.
  bool assign_unlabelled = true;   // Step 3d (only with unlabelled points given).
  double unlabelled_min_distance = 0.0;  // Skeleton units: the assignment gates' floor;
                                         // <= 0: outlier_distance / 2.
  double unlabelled_max_distance = 0.0;  // Skeleton units: their cap; <= 0: 1.25 outlier_distance.
  int unlabelled_min_frames = 3;   // Frames an assignment needs when it continues no observed sample.
  int trim_max = 120;              // Frames, per side of a gap.
  int small_track = 120;           // Frames.
  int small_gap = 5;               // Frames.
  double velocity_clamp = 0.0;     // Skeleton units per frame (<= 0: no clamp).
  int edge_samples = 1;            // Per gap edge, for the offset velocity (1: none; signal/gap_fill.h).
  GapFillKind fill = GapFillKind::kKriging;  // Step 6: how a gap's offset from X^ is filled.
  int fill_samples = 10;           // kKriging: samples of the offset conditioned on per side.
  bool refit_reference = true;     // Step 6, kTracker: X^ refitted without the cut samples
                                   // for smooth runs and gaps (marker_repair.cc).
  double refit_rough_factor = 3.0;  // A cut run rougher than this (median |second difference|
                                    // against the marker's own) is filled from X^ as solved.
  double rough_extension_factor = 6.0;  // A rough run is extended over the samples beside it whose
                                        // residual |second difference| exceeds this times the
                                        // marker's median (and a tenth of the gates' floor),
                                        // up to trim_max per side (0: off;
                                        // signal/rough_run_extension.h).
  bool carry_joints = true;        // Step 6: joints no kept marker observes carried across
                                   // their runs in joint space (signal/joint_gap_carry.h).
  // The warm start of every frame-by-frame solve's first frame; empty: the rest pose. A
  // window of a long take (pipeline/take_windows.h) starts from the previous window's solve
  // of the frame before it: a joint whose twist the markers leave free is held near its
  // warm start, so a cold start can hold it elsewhere for the whole window.
  Pose start_pose;

  // Every number finite, the thresholds positive, the frame counts >= 0, and the solve
  // options valid; otherwise false with a one-line reason in *error.
  bool IsValid(std::string* error) const;
};

struct RepairInterval {
  int marker = 0;
  int first = 0, last = 0;  // Frames, inclusive.
  std::string what;         // "missing", "swap", "unlabelled", "outlier", "joint difference" (detected); "reference",
                            // "polynomial" (filled); "reference only" (whole take).
};

struct RepairStageTime {
  std::string stage;  // Named after the thesis' Table 2 where it has a counterpart.
  double seconds = 0.0;
};

struct RepairReport {
  // Intervals found (before preprocessing): gaps ("missing", "outlier", "joint
  // difference") and relabelled samples ("swap": the label that received them; a label
  // that gave its sample away and got none is a "swap" gap).
  std::vector<RepairInterval> detected;
  std::vector<MarkerSwap> swaps;  // Step 3c, markers as indices of the set.
  // Step 3d: runs of frames in which a missing marker took an unlabelled track's points
  // (also in `detected` as "unlabelled" intervals of the marker).
  std::vector<UnlabelledAssignment> unlabelled;
  std::vector<RepairInterval> filled;    // Gaps filled (after preprocessing).
  // Step 6, carry_joints: joints whose observing markers were all cut or missing, carried
  // in joint space over these frames (the filled markers come from that motion).
  std::vector<CarriedJointRun> carried;
  std::vector<RepairStageTime> timings;
  int trimmed_samples = 0, removed_track_samples = 0, polynomial_samples = 0;
  int rough_extension_samples = 0;  // Samples cut beside rough runs (signal/rough_run_extension.h).
  double naive_rms = 0.0, reference_rms = 0.0, repaired_rms = 0.0;  // Skeleton units.
  int resolved_frames = 0;  // Frames step 7 solved again (the others are Y's).
  int naive_unconverged_frames = 0;  // Frames whose naive solve stopped at the iteration limit.
  // Per joint: frames the naive solve held at the subject's mean pose as a hidden joint
  // (SequenceSolveReport::held_frames; empty when none was).
  std::vector<int> naive_held_frames;
  std::vector<int> naive_twist_held_frames;  // SequenceSolveReport::twist_held_frames, the same.
};

// What the pipeline computed on the way, for evaluation (repair_evaluation.h).
struct RepairIntermediates {
  Motion naive;      // Y.
  Motion reference;  // Y^.
  std::vector<std::vector<Eigen::Vector3d>> reconstructed;  // X^ = LBS(Y^, Z).
  MarkerResidualModel residual_model;  // Step 3b.
};

// The observations observed[f][m] as trajectories labelled by the marker set (NaN =
// missing), and back.
MarkerTrajectories ObservationTrajectories(const MarkerSet& markers,
                                           const std::vector<std::vector<Eigen::Vector3d>>& observed);
std::vector<std::vector<Eigen::Vector3d>> TrajectoryObservations(const MarkerTrajectories& trajectories);

// Progress for a display: (stage, done, total) in frames, during the naive solve and
// around the re-solve.
using RepairProgress = std::function<void(const std::string& stage, int done, int total)>;

// Error unless observed has >= 1 frame, each of the marker set's size (checked first by
// RepairMarkers and EvaluateRepair: a take of 0 frames has nothing to solve or repair).
Status CheckRepairObservations(const MarkerSet& markers, const std::vector<std::vector<Eigen::Vector3d>>& observed);

// observed[f][m]: marker m of the set at frame f (NaN = missing). Writes the repaired
// observations (same layout), the re-solved motion, and the report.
Status RepairMarkers(const Skeleton& skeleton, const MarkerSet& markers,
                     const std::vector<std::vector<Eigen::Vector3d>>& observed,
                     const RepairOptions& options, std::vector<std::vector<Eigen::Vector3d>>* repaired,
                     Motion* motion, RepairReport* report,
                     RepairIntermediates* intermediates = nullptr,
                     const RepairProgress& progress = nullptr);
// The same with the take's unlabelled points (step 3d; their frame count must be the
// observations', or no tracks).
Status RepairMarkers(const Skeleton& skeleton, const MarkerSet& markers,
                     const std::vector<std::vector<Eigen::Vector3d>>& observed,
                     const UnlabelledPoints& unlabelled, const RepairOptions& options,
                     std::vector<std::vector<Eigen::Vector3d>>* repaired, Motion* motion, RepairReport* report,
                     RepairIntermediates* intermediates = nullptr, const RepairProgress& progress = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_MARKER_REPAIR_H_
