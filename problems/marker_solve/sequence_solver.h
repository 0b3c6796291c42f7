// Frame-by-frame solving of a whole take: each frame is warm-started from the previous
// frame's solution (and, with a prior, pulled toward it). The first frame starts from a
// coarse search (or, with root_from_markers, from the markers' geometry): the root is placed at the markers' centroid and tried in the 24
// axis-aligned orientations (when it has three rotation dofs), and the best solve is
// kept, so a take need not start near the skeleton's rest orientation. The search is
// plain least squares even when the options ask for a robust loss (see InitialPose), and
// always runs on the lean DLS kernel, so that every solver starts the take from one pose.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SEQUENCE_SOLVER_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SEQUENCE_SOLVER_H_

#include <functional>
#include <vector>

#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

struct SequenceSolveReport {
  int frames = 0;
  int unsolved_frames = 0;       // No marker observed, or the solver failed: pose kept.
  int unconverged_frames = 0;    // Hit the iteration limit.
  long total_iterations = 0;
  double solve_seconds = 0.0;    // Excluding the first frame's orientation search.
  double rms_marker_error = 0.0;  // Over every observed sample, skeleton units.
  double max_frame_rms = 0.0;
  double total_final_cost = 0.0;
  std::vector<double> frame_rms;  // Per frame.
  std::vector<double> frame_cost;  // Per frame: the solver's final cost (NaN where unsolved).
  // Per joint: the frames in which it was held toward the subject's mean pose as a hidden
  // joint (MarkerSolveOptions::hidden_rotation_weight; empty when none was).
  std::vector<int> held_frames;
  // Per joint: the frames in which it was held about the line to its one seen marker
  // (MarkerSolveOptions::twist_rotation_weight; empty when none was).
  std::vector<int> twist_held_frames;
};

// observed[f][m] in model units (MarkerObservations); `initial` is the starting pose (but
// for the joints InitialPose puts at the rest prior's reference). motion receives one pose
// per frame.
Status SolveSequence(const Skeleton& skeleton, const MarkerSet& markers,
                     const std::vector<std::vector<Eigen::Vector3d>>& observed,
                     const MarkerSolveOptions& options, const Pose& initial, Motion* motion,
                     SequenceSolveReport* report,
                     const std::function<void(int frames_done)>& progress = nullptr,
                     bool root_from_markers = false);

// The first frame's start: with the rest prior on (options.rest_rotation_weight > 0 and
// rest_rotations given, the subject's mean pose), every joint no marker moves (none on it or
// below it) at its reference, where that prior alone holds it (from zero rotations it
// stayed there: an ASF subject's unobserved arm in a T-pose); the best of 24 root
// orientations, root at the marker centroid;
// with root_from_markers, only the root pose from the markers' own geometry
// (RootPoseFromMarkers), which cannot lock onto a wrong axis orientation that a free
// fit of offsets happens to match better.
Status InitialPose(const Skeleton& skeleton, const MarkerSet& markers,
                   const std::vector<Eigen::Vector3d>& observed, const MarkerSolveOptions& options,
                   Pose* pose, bool root_from_markers = false);

// The root rotation and translation that rigidly align the markers as *pose places them
// to the observed ones (least squares, Kabsch/Umeyama without scale, over the markers
// observed; at least 3 not collinear): the person's facing and tilt from the markers'
// geometry (pelvis, spine and limbs together). Other joints are left as they are.
Status RootPoseFromMarkers(const Skeleton& skeleton, const MarkerSet& markers,
                           const std::vector<Eigen::Vector3d>& observed, Pose* pose);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SEQUENCE_SOLVER_H_
