// What a failed quality gate is to blame on, and what to try: the gate's marker checks
// (naive and repaired marker RMS, repaired share) give one figure for the whole take; this
// says which markers and frames carry it.
//
// Per marker of the subject: e_m(f) = |x_m(f) - M_m(pose(f))|, the captured sample against
// its model position on the solved motion, over the frames where it was captured;
//   rms_m   = sqrt(mean_f e_m(f)^2)                          (mm),
//   share_m = sum_f e_m(f)^2 / sum_{m', f} e_m'(f)^2          (of the take's squared error),
//   worst   = the one-second window of frames with the largest sum of e_m(f)^2.
// Markers are listed by share, largest first. The advice follows the shares: when a few
// markers carry most of the error, they (their labels, their placement on this actor) are
// the cause; when it is spread over the markers, the subject does not fit this actor.
#ifndef MOCAPSOLVE_PIPELINE_GATE_BLAME_H_
#define MOCAPSOLVE_PIPELINE_GATE_BLAME_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

struct MarkerBlame {
  std::string label;
  double rms_mm = 0.0;
  double share = 0.0;                  // Of the take's squared error, 0..1.
  int worst_first = 0, worst_last = 0;  // Frames, inclusive.
};

// observed[f][m] (NaN = missing) in skeleton units; mm = millimetres per skeleton unit.
std::vector<MarkerBlame> BlameMarkers(const Skeleton& skeleton, const MarkerSet& markers,
                                      const std::vector<std::vector<Eigen::Vector3d>>& observed, const Motion& solved,
                                      double mm);

// One line for a person: the markers carrying half of the error (at most five) with their
// RMS, share and worst frames, and what to try (`markers`: the take's path as given, for
// the command line it suggests). With `subject_from_take` (the subject was fitted on this
// take, --subject=auto) it does not suggest fitting one on the take; an error spread over
// the markers suggests fitting on every frame (--fit_max_frames=0) instead.
std::string GateAdvice(const std::vector<MarkerBlame>& blame, const std::string& markers,
                       bool subject_from_take = false);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_GATE_BLAME_H_
