// Leave-one-marker-out: how well the solved model predicts each marker it was not given,
// a measure of solve accuracy on real takes that needs no ground truth (issue 16).
//
// For each marker m of the set: drop m from every frame, solve the take without it
// (frame by frame as `solve` does, SolveSequence; with `clip`, then the whole-clip solve
// from that start, SolveClip), and predict m from the solution through its attachment:
// x^_m(f) = MarkerSet::Position(m, FK(pose_f)). The prediction error of m at frame f is
// |x^_m(f) - x_m(f)| over the frames where m was observed. A marker the model places well
// from the others is predicted within the soft-tissue and calibration error; a marker
// the solution does not constrain (its bone moved by it alone) shows it.
//
// No sample of m reaches its prediction: the solves see `observed` with m missing, and with
// refine_rounds > 0 the other markers' offsets are re-estimated on the take between solves
// (offset_refinement.h: each towards its calibrated offset; m, unobserved, keeps its own),
// x^_m(f) then coming from the last solve. With off_body_tolerance > 0 the other markers'
// samples that the body cannot have put where they are (problems/marker_label/
// off_body_samples.h: further from another marker than the skeleton reaches, by more than the
// tolerance; a marker fallen off, a point on the floor) are left out of those solves, so an
// impossible sample does not drag the pose that predicts m (nick_freeform_001's RTOE, 0.8-1.4
// m from its ankle in 115 frames). They are found on the observations without m, so m's own
// samples decide nothing; m is scored on all its samples, flagged or not (its
// PredictionErrorSummary::off_body counts those flagged with every marker present). Which frames and subject are given is the caller's
// protocol (tasks/evaluate_task.h: the subject from another take, or from the take's first
// half with the second half given here).
//
// Summaries (mean, median, 95th percentile, max) per marker and over every sample of
// every marker. Lengths in skeleton units. Each marker's solve is independent of the
// others', so the markers are spread over num_threads threads and the result does not
// depend on their number.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LEAVE_ONE_OUT_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LEAVE_ONE_OUT_H_

#include <functional>
#include <string>
#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_solve/marker_clip_solver.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "problems/marker_solve/offset_refinement.h"

namespace mocapsolve {

struct LeaveOneOutOptions {
  MarkerSolveOptions frame;  // The per-frame solve.
  bool clip = false;         // Then the whole-clip solve with `clip_options`.
  ClipSolveOptions clip_options;
  int num_threads = 1;       // Markers solved at once.
  int refine_rounds = 0;     // Offset refinements (each followed by a solve) per left-out marker.
  OffsetRefinementOptions refine;
  bool keep_predictions = false;  // Fill LeaveOneOutReport::predicted.
  double off_body_tolerance = 0.0;  // Skeleton units; 0: every sample of the others solved.
};

struct PredictionErrorSummary {
  int samples = 0;  // Frames where the marker was observed (and so could be scored).
  int off_body = 0;  // Of those, samples off the body (with the others; off_body_tolerance > 0).
  double mean = 0.0, median = 0.0, p95 = 0.0, max = 0.0;  // Skeleton units.
};

struct LeaveOneOutReport {
  std::vector<PredictionErrorSummary> markers;  // Per marker of the set.
  PredictionErrorSummary all;                   // Over every scored sample.
  double seconds = 0.0;                         // Wall time of all the solves.
  // With keep_predictions: predicted[m][f], x^_m(f) where m was observed, else NaN.
  std::vector<std::vector<Eigen::Vector3d>> predicted;
};

// The summary of a set of errors (empty: all zero). Sorts `errors`.
PredictionErrorSummary SummarizeErrors(std::vector<double>* errors);

// One marker's part of LeaveOneMarkerOut: the take solved without marker m (as `options`
// say; num_threads and keep_predictions unused) and *errors = |x^_m(f) - y_m(f)| over the
// frames where m was observed, in order; with `predicted` also x^_m(f) (NaN elsewhere).
Status LeftOutPredictionErrors(const Skeleton& skeleton, const MarkerSet& markers,
                               const std::vector<std::vector<Eigen::Vector3d>>& observed, int m,
                               const LeaveOneOutOptions& options, std::vector<double>* errors,
                               std::vector<Eigen::Vector3d>* predicted = nullptr);

// observed[f][m] in skeleton units (NaN = missing). progress(markers_done) after each
// marker's solves, from the calling thread.
Status LeaveOneMarkerOut(const Skeleton& skeleton, const MarkerSet& markers,
                         const std::vector<std::vector<Eigen::Vector3d>>& observed,
                         const LeaveOneOutOptions& options, LeaveOneOutReport* report,
                         const std::function<void(int markers_done)>& progress = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LEAVE_ONE_OUT_H_
