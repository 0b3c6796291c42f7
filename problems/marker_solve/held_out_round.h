// Which attach round of a skeleton fit to keep, by a held-out measure instead of the
// marker RMS the rounds minimise.
//
// The RMS a round reaches is fitted: every marker's offset absorbs its own samples, so a
// round that lets a joint chase a marker alone (a toe turned to follow its one metatarsal
// marker) or trades a bone length against marker offsets lowers it without placing the
// markers any better relative to each other. Which round had the lowest RMS then moves
// with every small change of the path (JA1Gait35's time split keeps round 4, cmu_02_05's
// round 10), and single markers predicted from the others swing by 30-200 mm between
// rounds whose RMS differs by 1 %.
//
// The held-out score of a round: the median, over the markers m and the scored frames f,
// of the leave-one-marker-out error |x^_m(f) - x_m(f)| (leave_one_out.h), each marker
// predicted by the per-frame solve of the others, on the round's model as a subject
// would hold it (lone joints regauged to their mean pose, lone_joint_gauge.h; the rest
// prior toward the round's mean pose, mean_pose.h). Frames: every k-th frame of the fit,
// k = ceil(frames / max_frames), so the score costs at most max_frames frame solves per
// marker. No sample is held out of the fit itself: the score is not free of the fit's own
// frames, but it scores a marker where the others put it, which is what a leave-one-out
// measure (and a later take) asks of the subject.
//
// The kept round (KeptRound): the latest candidate whose score is within `tolerance`
// (relative) of the lowest. A later round is preferred while the held-out measure does
// not tell it apart from the best (the score moves by about 1 % between rounds that are
// alike); one that scores clearly worse (a round that re-attached a marker badly) is not.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_HELD_OUT_ROUND_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_HELD_OUT_ROUND_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

struct HeldOutRoundOptions {
  int max_frames = 120;     // Frames scored (every k-th of the fit's).
  int num_threads = 2;      // Markers solved at once (the score does not depend on it).
  double tolerance = 0.05;  // KeptRound: relative margin to the lowest score.
};

// The held-out score (skeleton units) of a round's fit: `skeleton` and `markers` as
// fitted, `motion` the fit's motion over the frames of `observed` (observed[f][m],
// skeleton units, NaN = missing). `solve` is the per-frame solve of later takes; its rest
// prior is pointed at the round's mean pose when it needs a reference. Errors: those of
// FixLoneJointGauges and LeaveOneMarkerOut.
Status HeldOutRoundScore(const Skeleton& skeleton, const MarkerSet& markers, const Motion& motion,
                         const std::vector<std::vector<Eigen::Vector3d>>& observed, MarkerSolveOptions solve,
                         const HeldOutRoundOptions& options, double* score);

// The index of the latest score within (1 + tolerance) times the lowest (-1 when empty).
int KeptRound(const std::vector<double>& scores, double tolerance);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_HELD_OUT_ROUND_H_
