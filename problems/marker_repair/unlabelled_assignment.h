// Unlabelled points labelled (issue 16 item 3): the "marker tracking" stage the thesis
// names before solving. A capture carries unlabelled points (C3D "*52", "*53": the
// tracker saw a point but could not name it) while labelled markers drop out; where the
// kinematic prediction says an unlabelled point is a missing marker, it becomes that
// marker's sample before gap filling.
//
// Input: the labelled samples x_fm (after swap detection; NaN = missing), the unlabelled
// tracks u_fk (track k of the file, NaN where it has no point), and the marker residual
// model (marker_residual_model.h): the soft-tissue prediction P_fm of every marker at
// every frame, the median deviation mu_m, robust scale s_m and step gate w_m. Per marker
// the assignment gate is
//   g_m = clamp(mu_m + k s_m, min_distance, max_distance)      (k = `mads`),
// and, in frame f, a point u_fk is a candidate for marker m when
//   m is missing at f,  d_fmk = |u_fk - P_fm| <= g_m,  and
//   d_fmk / g_m < |u_fk - P_fn| / g_n for every marker n observed at f
// (a point that fits a present marker at least as well is that marker's ghost).
// Per frame the candidates are matched one to one, maximizing sum (1 - d_fmk / g_m) over
// the matched pairs (a pair at the gate gains nothing): an assignment problem on the
// frame's candidate markers x points, solved exactly by the Hungarian method with one
// "unmatched" column per marker at cost 1.
// Continuity: the frames where marker m took points of track k form runs of consecutive
// frames. Along the track y (m's observed samples before the run, then the run's points), a
// step y_f - y_(f-1) is continuous when it departs by at most the continuity tolerance
// c_m = max(w_m, min_distance / 2) from the prediction's step or from the track's previous
// step (constant velocity; the prediction alone jumps where the reference's pose changes
// because a marker left or came back):
//   |(y_f - y_(f-1)) - (P_fm - P_(f-1)m)| <= c_m  or  |(y_f - y_(f-1)) - (y_(f-1) - y_(f-2))| <= c_m.
// A run is split at a step that is not continuous, and the same test at a run's ends
// against m's observed samples next to it decides whether the run continues m's track:
// a run is kept when no observed neighbour is
// discontinuous with it and it has at least min_frames frames or a continuous observed
// neighbour (a single frame that bridges an observed track is kept; a lone point with
// nothing to continue is not). Kept runs become m's samples (an observed sample is never
// overwritten) and are reported as assignments. Lengths are skeleton units.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_UNLABELLED_ASSIGNMENT_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_UNLABELLED_ASSIGNMENT_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_trajectories.h"
#include "problems/marker_repair/marker_residual_model.h"

namespace mocapsolve {

// The unlabelled tracks of a take: names[k] ("*52") and points[f][k] (#F by #K, skeleton
// frame and units, NaN where track k has no point at frame f). Empty: none.
struct UnlabelledPoints {
  std::vector<std::string> names;
  std::vector<std::vector<Eigen::Vector3d>> points;

  int num_tracks() const { return static_cast<int>(names.size()); }
  bool present(int f, int k) const {
    return f < static_cast<int>(points.size()) && points[f][k].allFinite();
  }
};

struct UnlabelledAssignmentOptions {
  double mads = 6.0;          // k of the gate.
  double min_distance = 0.0;  // Skeleton units: the gate's floor (> 0).
  double max_distance = 0.0;  // Skeleton units: the gate's cap (>= min_distance).
  int min_frames = 3;         // A run with no continuous observed neighbour needs this many frames.
};

// One run of frames in which marker `marker` took the points of unlabelled track `track`.
struct UnlabelledAssignment {
  int marker = 0, track = 0;
  int first = 0, last = 0;       // Frames, inclusive.
  double mean_distance = 0.0;    // Mean |u - P| over the run (skeleton units).
};

// Assigns and writes the kept runs into *x (only at missing samples); returns them ordered
// by marker, then first frame. points.size() must be x's frame count (or 0 tracks).
std::vector<UnlabelledAssignment> AssignUnlabelledPoints(const MarkerResidualModel& model,
                                                         const UnlabelledPoints& unlabelled,
                                                         const UnlabelledAssignmentOptions& options,
                                                         MarkerTrajectories* x);

// Minimum-cost assignment of rows to columns (rows <= columns; cost[r][c] finite): the
// column of each row. Hungarian method (Kuhn-Munkres with potentials), O(rows^2 columns).
std::vector<int> MinimumCostAssignment(const std::vector<std::vector<double>>& cost);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_UNLABELLED_ASSIGNMENT_H_
