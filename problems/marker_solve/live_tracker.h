// LiveTracker: joint angles frame by frame as the frames arrive, with no look-ahead and a
// bounded look-back: each frame is solved by MarkerFrameSolver warm-started from (and,
// with a prior, pulled toward) the previous frame's pose; the first frame with markers
// starts from InitialPose's coarse search (sequence_solver.h).
//
// Missing markers are predicted: a marker not observed in this frame but observed within
// the last `predict_frames` frames enters the solve at its constant-velocity prediction,
//   x_pred(k) = x(k1) + (k - k1) * (x(k1) - x(k0)) / (k1 - k0),
// from its last two samples k0 < k1 (velocity zero when they are more than 2 frames
// apart or there is one sample), so a short occlusion does not let the limb's twist or
// bend drift; after that it is left out until it returns. The look-back is those two
// samples per marker and the previous pose, nothing else.
//
// A frame with no marker observed or predicted, or whose solve fails, keeps the previous
// pose (counted as unsolved). Observations are in the skeleton's frame and units
// (MarkerFileToModel applied by the caller), NaN = missing.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LIVE_TRACKER_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LIVE_TRACKER_H_

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

struct LiveTrackReport {
  int markers_observed = 0;
  int markers_predicted = 0;
  bool solved = false;          // False: the previous pose was kept.
  int iterations = 0;
  double rms_marker_error = 0.0;  // Over the observed markers (not the predicted), skeleton units.
};

class LiveTracker {
 public:
  // Keeps references to the skeleton and marker set: they must outlive the tracker.
  LiveTracker(const Skeleton& skeleton, const MarkerSet& markers, const MarkerSolveOptions& options,
              int predict_frames);

  // The next frame's observations (one per marker of the set); *pose receives its pose.
  Status Track(const std::vector<Eigen::Vector3d>& observed, Pose* pose, LiveTrackReport* report);

 private:
  struct History {
    long k0 = -1, k1 = -1;  // Frames of the last two samples (-1: none).
    Eigen::Vector3d x0, x1;
  };

  const Skeleton& skeleton_;
  const MarkerSet& markers_;
  MarkerSolveOptions options_;
  int predict_frames_;
  MarkerFrameSolver solver_;
  Pose pose_;
  bool started_ = false;
  long frame_ = 0;
  std::vector<History> history_;
  std::vector<Eigen::Vector3d> filled_;  // Observed or predicted, per marker.
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LIVE_TRACKER_H_
