// Marker labelling: which marker of a subject each point of a raw point cloud is, frame by
// frame (the "marker tracking" stage before solving). Input: the subject's skeleton and
// marker set and, per frame, the points in any order and number (ghosts, dropouts), in the
// skeleton's frame and units.
//
// 1. Find the body (label_acquisition.h) in the first frame where it can be found (at most
//    `acquire_frames` tried; none: an error naming the best match). A point matched there
//    to a marker m goes to an empty marker n when, from the pose solved without it (the
//    joints of m and n started again from the mean pose), n's model position is within
//    `gate` of it and less than half as far as m's: a marker absent from the take (a heel
//    marker whose foot mates are absent too) can hold a neighbour's point at one frame at
//    no cost, the ankle marker left empty, and tracking would keep it.
// 2. Track forward from there to the last frame, then backward to the first. Per frame,
//    each marker is predicted: labelled in the two previous frames, at constant velocity
//      p_m = x_m(f-1) + (x_m(f-1) - x_m(f-2))                       within `gate`;
//    labelled in the previous frame only, p_m = x_m(f-1) + s_m, with s_m the model's step
//    (M_m(pose(f-1)) - M_m(pose(f-2))), within `reacquire_gate`; otherwise from the
//    kinematic model, the pose solved at the previous frame plus the marker's offset from
//    its model position when it was last labelled,
//      p_m = M_m(pose(f-1)) + s_m + (x_m(f') - M_m(pose(f')))         within `reacquire_gate`.
//    Points and predictions are matched one to one (gated_assignment.h: gated, a cost for
//    an empty label); a match whose confidence is below `min_confidence` leaves the point
//    unlabelled rather than guess. A joint's markers that miss their constant-velocity
//    gates together (two or more of a rigid cluster, >= 3 markers on one joint: a kick's
//    onset) are placed again as a cluster among the free points within `reacquire_gate` of
//    their predictions (and the points its other markers took): the one-to-one choice
//    whose rigid fit to the cluster's points at f-1 leaves an RMS residual under 0.4 `gate`
//    and turns the joint least (score residual^2/(0.4 gate)^2 + (turn/0.7 rad)^2 + empty
//    markers; taken when the next choice scores 0.5 more). Markers still without a confident point are matched
//    again among the free points from the pose solved from the confident matches (each
//    predicted with its last offset, within `gate`, kept at confidence >= 0.7). The pose
//    of the frame is solved from its labelled
//    points (MarkerFrameSolver, warm-started), for the next frame's model predictions.
//    Every `polish_every` frames the frame's matches are checked by PolishMatches
//    (label_acquisition.h: exchanges, 3-cycles and free points that lower the solved cost
//    by more than 1 %; an exchange of tracked labels is kept when the track's previous
//    frames agree by more than 5 % and the distances among the markers of one joint do not
//    move further from the subject's: |u_m - u_n| - |z_m - z_n|, RMS over those frames), and
//    at the acquisition and every `refill_every` frames the markers without a point look
//    for free points near the pose solved from the others (a lost limb comes back).
// 3. Losses: a frame where fewer than `lost_fraction` of the markers found at acquisition
//    are labelled loses the body; from the next frame the body is looked for again
//    (re-acquisition), each frame until found.
// Per marker the labeller counts samples labelled, conflicts the one-to-one assignment
// decided ("swaps avoided": nearest-point labelling would have given the marker another
// point or two markers one point), re-acquisitions (labelled again after >= 1 frame
// without a label) and matches refused for low confidence.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_LABEL_MARKER_LABELLER_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_LABEL_MARKER_LABELLER_H_

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_label/label_acquisition.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

struct LabellerOptions {
  double gate = 0.0;            // Skeleton units (> 0): markers labelled in the previous frame.
  double reacquire_gate = 0.0;  // Skeleton units (> 0): markers predicted by the model.
  double min_confidence = 0.2;  // Matches below it leave the point unlabelled.
  double lost_fraction = 0.4;   // Of the markers found at acquisition.
  int acquire_frames = 60;      // Frames tried to find the body at the start.
  int polish_every = 30;       // Frames between checks of the labels (PolishMatches); 0 = never.
  int refill_every = 30;       // Frames between searches for markers without a point; 0 = never.
  AcquisitionOptions acquisition;
  MarkerSolveOptions solve;
};

struct MarkerLabelStats {
  int labelled = 0;
  int swaps_avoided = 0;
  int reacquisitions = 0;
  int low_confidence = 0;
};

struct LabellingResult {
  std::vector<std::vector<int>> marker_of_point;  // [frame][point]: marker, -1 = unlabelled.
  std::vector<std::vector<float>> confidence;     // [frame][point]: of its label (0 unlabelled).
  std::vector<MarkerLabelStats> per_marker;       // #M.
  std::vector<int> acquisitions;                  // Frames where the body was found (first: the start).
  int lost_frames = 0;                            // Frames without the body.
  Acquisition first;                              // The first acquisition (or the best failed one).
  int first_frame = -1;                           // Its frame.
};

using LabelProgress = std::function<void(int done, int total)>;

// points[f]: frame f's points. mean_pose: the subject's (empty: identity rotations).
// Errors: the body not found in the first acquire_frames frames with points (the message
// gives the best match: markers matched of the set, RMS, frame).
Status LabelPointCloud(const Skeleton& skeleton, const MarkerSet& markers, const QuaternionVector& mean_pose,
                       const std::vector<std::vector<Eigen::Vector3d>>& points, const LabellerOptions& options,
                       const LabelProgress& progress, LabellingResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_LABEL_MARKER_LABELLER_H_
