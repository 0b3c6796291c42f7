#include "problems/marker_solve/sequence_solver.h"

#include <chrono>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/held_segments.h"
#include "problems/marker_solve/marker_observations.h"

namespace mocapsolve {

Status RootPoseFromMarkers(const Skeleton& skeleton, const MarkerSet& markers,
                           const std::vector<Eigen::Vector3d>& observed, Pose* pose) {
  FkData fk(skeleton);
  Pose start = *pose;
  start.rotations[0].setIdentity();
  start.translations[0].setZero();
  ForwardKinematics(skeleton, start, &fk);
  std::vector<int> seen;
  for (int m = 0; m < markers.num_markers(); ++m) {
    if (observed[m].allFinite()) seen.push_back(m);
  }
  if (seen.size() < 3) return Status::Error("fewer than 3 markers observed in the first frame");
  Eigen::Matrix3Xd model(3, seen.size()), world(3, seen.size());
  for (size_t i = 0; i < seen.size(); ++i) {
    model.col(i) = markers.Position(seen[i], fk);
    world.col(i) = observed[seen[i]];
  }
  const Eigen::Matrix4d world_from_model = Eigen::umeyama(model, world, false);
  if (!world_from_model.allFinite()) return Status::Error("the first frame's markers are degenerate");
  // Markers at rotation R of the root: p = t + R_rest R R_rest^T q (q as placed at R = I,
  // t = 0), so the aligning rotation Q gives R = R_rest^T Q R_rest.
  const Eigen::Quaterniond rest = skeleton.rest_rotation(0);
  const Eigen::Quaterniond q(Eigen::Matrix3d(world_from_model.topLeftCorner<3, 3>()));
  pose->rotations[0] = (rest.conjugate() * q * rest).normalized();
  pose->translations[0] = world_from_model.topRightCorner<3, 1>();
  return Status::Ok();
}

namespace {

// With the rest prior on, every joint of *pose that no marker moves (no marker on it or
// below it: a finger without a marker, a sparse set's unobserved arm; held_segments.h) put
// at the prior's reference (the subject's mean pose). Only that prior pulls such a joint,
// far too weakly against the damping to move it from where it starts: from zero rotations
// an ASF subject's unobserved arm stayed in a T-pose. No marker's residual depends on it.
void StartUnmovedJointsAtRest(const Skeleton& skeleton, const MarkerSet& markers, const MarkerSolveOptions& options,
                              Pose* pose) {
  if (!(options.rest_rotation_weight > 0.0) ||
      options.rest_rotations.size() != static_cast<size_t>(skeleton.num_joints()) ||
      pose->rotations.size() != options.rest_rotations.size()) {
    return;
  }
  const std::vector<bool> moved = ObservedJoints(skeleton, markers);
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    if (!moved[j]) pose->rotations[j] = options.rest_rotations[j].normalized();
  }
}

}  // namespace

Status InitialPose(const Skeleton& skeleton, const MarkerSet& markers,
                   const std::vector<Eigen::Vector3d>& observed, const MarkerSolveOptions& options,
                   Pose* pose, bool root_from_markers) {
  StartUnmovedJointsAtRest(skeleton, markers, options, pose);
  if (root_from_markers && skeleton.num_rotation_dofs(0) == 3) {
    Pose start = *pose;
    Status status = RootPoseFromMarkers(skeleton, markers, observed, &start);
    if (status.ok()) {
      MarkerSolveOptions search = options;
      search.prior_rotation_weight = search.prior_translation_weight = search.rest_rotation_weight =
          search.hidden_rotation_weight = 0.0;
      search.solver = SolverKind::kDls;  // One start for every solver (see InitialPose's search).
      MarkerFrameSolver solver(skeleton, markers, search);
      FrameSolveReport report;
      if (solver.Solve(observed, &start, &report).ok()) {
        *pose = start;
        return Status::Ok();
      }
    }
  }
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  int n = 0;
  for (const auto& x : observed) {
    if (x.allFinite()) centroid += x, ++n;
  }
  if (n == 0) return Status::Error("no marker observed in the first frame");
  centroid /= n;
  // The cold start is about the markers alone: no pull toward the previous frame or the rest
  // pose (with the rest prior, the 24 starts of 02_01 could end in a wrong basin that the
  // first frame then kept: Ceres' tracker at 9.5 mm instead of 4.0 at exactly 5 mm/rad).
  MarkerSolveOptions search = options;
  search.prior_rotation_weight = search.prior_translation_weight = search.rest_rotation_weight =
      search.hidden_rotation_weight = 0.0;
  // Plain least squares for the cold start: a robust loss (the repair's reference) makes
  // a limb posed wrongly a cheap local minimum, which a tracker pulled toward the previous
  // frame then keeps (Ceres' Cauchy at 1 cm held 02_01's left forearm wrong for 65
  // frames). The first frame's own solve then applies the loss from this start.
  search.loss = "none";
  // One search for every solver: the lean DLS kernel's, whatever options.solver is, so that
  // Ceres and DLS start the take from the same pose. (Each ran its own search before: on
  // cmu_02_05 the two ended the first frame in different places of the directions only the
  // rest prior decides, which the warm start then carried through the take, a cost a
  // third apart on every frame at the same marker RMS.)
  search.solver = SolverKind::kDls;
  MarkerFrameSolver solver(skeleton, markers, search);
  double best = std::numeric_limits<double>::infinity();
  Pose best_pose;
  // A root that cannot rotate freely keeps the orientation it was given.
  const std::vector<Eigen::Matrix3d> orientations =
      skeleton.num_rotation_dofs(0) == 3 ? AllAxisRotations()
                                         : std::vector<Eigen::Matrix3d>{pose->rotations[0].toRotationMatrix()};
  for (const Eigen::Matrix3d& axes : orientations) {
    const Eigen::Quaterniond orientation(axes);
    Pose candidate = *pose;
    candidate.rotations[0] = orientation;
    // Put the rest markers' centroid on the observed one.
    FkData fk(skeleton);
    candidate.translations[0].setZero();
    ForwardKinematics(skeleton, candidate, &fk);
    Eigen::Vector3d model_centroid = Eigen::Vector3d::Zero();
    for (int m = 0; m < markers.num_markers(); ++m) {
      if (observed[m].allFinite()) model_centroid += markers.Position(m, fk);
    }
    candidate.translations[0] = centroid - model_centroid / n;
    FrameSolveReport report;
    if (!solver.Solve(observed, &candidate, &report).ok()) continue;
    if (report.final_cost < best) {
      best = report.final_cost;
      best_pose = candidate;
    }
  }
  if (!std::isfinite(best)) return Status::Error("the first frame could not be solved");
  *pose = best_pose;
  return Status::Ok();
}

// One more frame for each of `joints` in *frames (per joint; made on first use, so a
// take where nothing is held reports an empty list).
namespace {
void CountFrames(const std::vector<int>& joints, int num_joints, std::vector<int>* frames) {
  for (int j : joints) {
    if (frames->empty()) frames->assign(num_joints, 0);
    ++(*frames)[j];
  }
}
}  // namespace

Status SolveSequence(const Skeleton& skeleton, const MarkerSet& markers,
                     const std::vector<std::vector<Eigen::Vector3d>>& observed,
                     const MarkerSolveOptions& options, const Pose& initial, Motion* motion,
                     SequenceSolveReport* report,
                     const std::function<void(int frames_done)>& progress, bool root_from_markers) {
  std::string error;
  if (!options.IsValid(&error)) return Status::Error(error);
  *report = SequenceSolveReport();
  report->frames = static_cast<int>(observed.size());
  motion->frames.assign(observed.size(), initial);
  if (observed.empty()) return Status::Ok();
  Pose pose = initial;
  // Start from the first frame that has markers.
  size_t first = 0;
  while (first < observed.size()) {
    bool any = false;
    for (const auto& x : observed[first]) any |= x.allFinite();
    if (any) break;
    ++first;
  }
  if (first == observed.size()) return Status::Error("no marker observed in any frame");
  Status status = InitialPose(skeleton, markers, observed[first], options, &pose, root_from_markers);
  if (!status.ok()) return status;

  MarkerFrameSolver solver(skeleton, markers, options);
  const int max_iterations = options.solver == SolverKind::kCeres ? options.ceres.max_num_iterations
                                                                  : options.dls.max_iterations;
  double sum_sq = 0.0;
  long samples = 0;
  report->frame_rms.assign(observed.size(), std::nan(""));
  report->frame_cost.assign(observed.size(), std::nan(""));
  const auto start = std::chrono::steady_clock::now();
  for (size_t f = 0; f < observed.size(); ++f) {
    FrameSolveReport frame;
    Pose attempt = pose;
    if (f < first || !solver.Solve(observed[f], &attempt, &frame).ok()) {
      ++report->unsolved_frames;
    } else {
      pose = attempt;
      report->total_iterations += frame.iterations;
      report->total_final_cost += frame.final_cost;
      CountFrames(frame.held_joints, skeleton.num_joints(), &report->held_frames);
      CountFrames(frame.twist_held_joints, skeleton.num_joints(), &report->twist_held_frames);
      if (frame.iterations >= max_iterations) ++report->unconverged_frames;
      report->frame_rms[f] = frame.rms_marker_error;
      report->frame_cost[f] = frame.final_cost;
      report->max_frame_rms = std::max(report->max_frame_rms, frame.rms_marker_error);
      sum_sq += frame.rms_marker_error * frame.rms_marker_error * frame.markers_used;
      samples += frame.markers_used;
    }
    motion->frames[f] = pose;
    if (progress) progress(static_cast<int>(f) + 1);
  }
  report->solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report->rms_marker_error = samples > 0 ? std::sqrt(sum_sq / samples) : 0.0;
  MakeSignContinuous(motion);
  return Status::Ok();
}

}  // namespace mocapsolve
