#include "problems/marker_solve/live_tracker.h"

#include <cmath>
#include <limits>

#include "problems/marker_solve/sequence_solver.h"

namespace mocapsolve {

LiveTracker::LiveTracker(const Skeleton& skeleton, const MarkerSet& markers, const MarkerSolveOptions& options,
                         int predict_frames)
    : skeleton_(skeleton),
      markers_(markers),
      options_(options),
      predict_frames_(predict_frames),
      solver_(skeleton, markers, options),
      pose_(RestPose(skeleton)),
      history_(markers.num_markers()),
      filled_(markers.num_markers()) {}

Status LiveTracker::Track(const std::vector<Eigen::Vector3d>& observed, Pose* pose, LiveTrackReport* report) {
  *report = LiveTrackReport();
  const long k = frame_++;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int m = 0; m < markers_.num_markers(); ++m) {
    History& h = history_[m];
    if (observed[m].allFinite()) {
      filled_[m] = observed[m];
      h.k0 = h.k1, h.x0 = h.x1;
      h.k1 = k, h.x1 = observed[m];
      ++report->markers_observed;
      continue;
    }
    filled_[m].setConstant(nan);
    if (!started_ || h.k1 < 0 || k - h.k1 > predict_frames_) continue;
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
    if (h.k0 >= 0 && h.k1 - h.k0 <= 2) velocity = (h.x1 - h.x0) / static_cast<double>(h.k1 - h.k0);
    filled_[m] = h.x1 + static_cast<double>(k - h.k1) * velocity;
    ++report->markers_predicted;
  }
  if (report->markers_observed + report->markers_predicted == 0) {
    *pose = pose_;
    return Status::Ok();
  }
  if (!started_) {
    if (report->markers_observed == 0 ||
        !InitialPose(skeleton_, markers_, filled_, options_, &pose_, /*root_from_markers=*/true).ok()) {
      *pose = pose_;
      return Status::Ok();
    }
    started_ = true;
  }
  Pose attempt = pose_;
  FrameSolveReport frame;
  if (solver_.Solve(filled_, &attempt, &frame).ok() && frame.usable) {
    // Keep each rotation on the previous one's hemisphere (sign-continuous quaternions).
    for (size_t j = 0; j < attempt.rotations.size(); ++j) {
      if (attempt.rotations[j].coeffs().dot(pose_.rotations[j].coeffs()) < 0) {
        attempt.rotations[j].coeffs() *= -1.0;
      }
    }
    pose_ = attempt;
    report->solved = true;
    report->iterations = frame.iterations;
    report->rms_marker_error = RmsMarkerError(skeleton_, markers_, pose_, observed);
  }
  *pose = pose_;
  return Status::Ok();
}

}  // namespace mocapsolve
