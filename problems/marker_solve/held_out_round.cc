#include "problems/marker_solve/held_out_round.h"

#include <algorithm>
#include <string>

#include "problems/marker_solve/leave_one_out.h"
#include "problems/marker_solve/lone_joint_gauge.h"
#include "problems/marker_solve/mean_pose.h"

namespace mocapsolve {

Status HeldOutRoundScore(const Skeleton& skeleton, const MarkerSet& markers, const Motion& motion,
                         const std::vector<std::vector<Eigen::Vector3d>>& observed, MarkerSolveOptions solve,
                         const HeldOutRoundOptions& options, double* score) {
  if (observed.empty() || motion.num_frames() != static_cast<int>(observed.size())) {
    return Status::Error("held-out round score: the motion and the observations differ in frames");
  }
  MarkerSet held = markers;
  Motion held_motion = motion;
  std::vector<std::string> regauged;
  Status status = FixLoneJointGauges(skeleton, &held, &held_motion, &regauged);
  if (!status.ok()) return status;
  if (solve.rest_prior_needs_reference || !solve.rest_rotations.empty()) {
    solve.rest_rotations = MeanPose(skeleton, held_motion);
  }
  const int frames = static_cast<int>(observed.size());
  const int max_frames = std::max(options.max_frames, 1);
  const int step = (frames + max_frames - 1) / max_frames;
  std::vector<std::vector<Eigen::Vector3d>> scored;
  for (int f = 0; f < frames; f += step) scored.push_back(observed[f]);
  LeaveOneOutOptions loo;
  loo.frame = solve;
  loo.num_threads = options.num_threads;
  LeaveOneOutReport report;
  status = LeaveOneMarkerOut(skeleton, held, scored, loo, &report);
  if (!status.ok()) return status;
  *score = report.all.median;
  return Status::Ok();
}

int KeptRound(const std::vector<double>& scores, double tolerance) {
  if (scores.empty()) return -1;
  const double lowest = *std::min_element(scores.begin(), scores.end());
  for (int i = static_cast<int>(scores.size()) - 1; i >= 0; --i) {
    if (scores[i] <= (1.0 + tolerance) * lowest) return i;
  }
  return -1;
}

}  // namespace mocapsolve
