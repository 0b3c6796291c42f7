// Per-take refinement of a calibrated subject's marker offsets: what a subject keeps
// (bone lengths, each marker's joint) is the actor's; where a marker sits on its joint moves a
// little between takes (the suit adjusted, the marker re-stuck, skin sliding in another kind
// of motion), so a later take may re-estimate it, held towards the calibrated value.
//
// Model. Marker m rides on joint j with offset z (joint j's frame, skeleton units):
// x_m(f) = p_j(f) + R_j(f) z (calibration.h). Given a solved motion of the take, the local
// position of each sample is l_m(f) = R_j(f)^T (y_m(f) - p_j(f)), and the refined offset
// minimises sum_f |z - l_m(f)|^2 + n0 |z - z0|^2 (z0: the calibrated offset, n0 =
// prior_frames: the calibration counts as n0 frames of observation):
//   z = (sum_f l_m(f) + n0 z0) / (n + n0),  n = the frames where m was observed.
// A marker with no sample in `observed` keeps z0 exactly (so a marker left out of the
// observations cannot be moved by them), as does a marker blended over several joints.
// A refined offset moves at most max_shift from z0 (skeleton units; 0: no bound), radially.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_OFFSET_REFINEMENT_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_OFFSET_REFINEMENT_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct OffsetRefinementOptions {
  double prior_frames = 200.0;  // n0 >= 0: the calibrated offset's weight, in frames.
  double max_shift = 0.0;       // Skeleton units; 0: unbounded.
};

struct OffsetRefinementReport {
  std::vector<double> shift;  // Per marker: |z - z0|, skeleton units (0: kept).
  int refined = 0;            // Markers whose offset was re-estimated.
};

// observed[f][m] in skeleton units (NaN = missing), motion.frames[f] the solved pose of frame
// f (same frame count). *refined: `calibrated` with the new offsets. Errors: frame counts
// or marker counts that do not match.
Status RefineMarkerOffsets(const Skeleton& skeleton, const MarkerSet& calibrated,
                           const std::vector<std::vector<Eigen::Vector3d>>& observed, const Motion& motion,
                           const OffsetRefinementOptions& options, MarkerSet* refined,
                           OffsetRefinementReport* report = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_OFFSET_REFINEMENT_H_
