#include "problems/retarget/retarget_clip.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "kinematics/skinning.h"

namespace mocapsolve {
namespace {

bool IsFootName(std::string name) {
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name.find("foot") != std::string::npos || name.find("toe") != std::string::npos;
}

// Foot skating (see the header), frame by frame: over consecutive frames (f - 1, f) and
// the foot vertices while the source's goals of both frames are in contact, the mean
// horizontal speed of the goals (source) and of the result's skinned vertices (result).
class FootSkatingSums {
 public:
  FootSkatingSums(const Skeleton& target_skeleton, const SkinnedMesh& target_mesh, const RetargetSetup& setup,
                  std::vector<int> feet, double contact_height, double frame_rate)
      : skeleton_(target_skeleton),
        mesh_(target_mesh),
        setup_(setup),
        feet_(std::move(feet)),
        floor_y_(setup.target_frame.origin.y()),
        contact_(contact_height * setup.target_frame.height),
        speed_scale_(frame_rate),
        height_(setup.target_frame.height),
        fk_(target_skeleton) {}

  bool active() const { return !feet_.empty() && speed_scale_ > 0.0; }

  // The frame's position goals and its solved pose, in frame order.
  void Add(const Eigen::Matrix3Xd& goals, const Pose& pose) {
    ForwardKinematics(skeleton_, pose, &fk_);
    ComputeSkinningTransforms(mesh_, fk_, &transforms_);
    skinned_.resize(3, static_cast<Eigen::Index>(setup_.tracked.size()));
    for (size_t s = 0; s < setup_.tracked.size(); ++s) {
      skinned_.col(s) = SkinPosition(mesh_, transforms_, setup_.tracked[s].target_vertex);
    }
    if (frames_ > 0) {
      for (int s : feet_) {
        if (previous_goals_(1, s) - floor_y_ >= contact_ || goals(1, s) - floor_y_ >= contact_) continue;
        source_sum_ += Speed(previous_goals_.col(s), goals.col(s));
        result_sum_ += Speed(previous_skinned_.col(s), skinned_.col(s));
        ++pairs_;
      }
    }
    previous_goals_ = goals;
    previous_skinned_.swap(skinned_);
    ++frames_;
  }

  int pairs() const { return pairs_; }
  double source() const { return pairs_ > 0 ? source_sum_ / pairs_ : 0.0; }
  double result() const { return pairs_ > 0 ? result_sum_ / pairs_ : 0.0; }

 private:
  double Speed(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return std::hypot(b.x() - a.x(), b.z() - a.z()) * speed_scale_ / height_;
  }

  const Skeleton& skeleton_;
  const SkinnedMesh& mesh_;
  const RetargetSetup& setup_;
  std::vector<int> feet_;
  double floor_y_, contact_, speed_scale_, height_;
  FkData fk_;
  std::vector<Eigen::Isometry3d> transforms_;
  Eigen::Matrix3Xd skinned_, previous_skinned_, previous_goals_;
  double source_sum_ = 0.0, result_sum_ = 0.0;
  int pairs_ = 0, frames_ = 0;
};

// The floor's lowest height for target joint k (options.floor_heights), -inf when the floor
// is off or k is no floor joint.
double LowestHeight(const RetargetSolveOptions& options, int k) {
  for (size_t i = 0; i < options.floor_joints.size(); ++i) {
    if (options.floor_weight > 0.0 && options.floor_joints[i] == k) return options.floor_heights[i];
  }
  return -std::numeric_limits<double>::infinity();
}

// The start pose, warm start and plants against the clip and the target skeleton.
Status CheckClipInputs(const Skeleton& target_skeleton, const RetargetClipOptions& options, const Pose& start,
                       int nf) {
  if (static_cast<int>(start.rotations.size()) != target_skeleton.num_joints() ||
      start.translations.size() != start.rotations.size()) {
    return Status::Error("retarget: the start pose does not match the target skeleton");
  }
  const bool warm_started = !options.warm_start.frames.empty();
  if (!options.run_solver && !warm_started) return Status::Error("retarget: no solve and no warm start");
  if (warm_started) {
    if (options.warm_start.num_frames() != nf) {
      return Status::Error("retarget: the warm start has " + std::to_string(options.warm_start.num_frames()) +
                           " frames, the source " + std::to_string(nf));
    }
    for (const Pose& p : options.warm_start.frames) {
      if (static_cast<int>(p.rotations.size()) != target_skeleton.num_joints() ||
          p.translations.size() != p.rotations.size()) {
        return Status::Error("retarget: the warm start does not match the target skeleton");
      }
    }
  }
  const int np = static_cast<int>(options.solve.plant_joints.size());
  if (static_cast<int>(options.plant_contacts.size()) != np) {
    return Status::Error("retarget: plant contacts given for " + std::to_string(options.plant_contacts.size()) +
                         " joints, plant joints " + std::to_string(np));
  }
  for (const std::vector<char>& contacts : options.plant_contacts) {
    if (static_cast<int>(contacts.size()) != nf) {
      return Status::Error("retarget: plant contacts do not cover the clip's frames");
    }
  }
  for (int k : options.solve.plant_joints) {
    if (k < 0 || k >= target_skeleton.num_joints()) return Status::Error("retarget: plant joint out of range");
  }
  const bool limbs_on = options.solve.limb_direction_weight > 0.0 && !options.solve.limbs.empty();
  if (limbs_on) {
    if (static_cast<int>(options.limb_goals.size()) != nf) {
      return Status::Error("retarget: limb goals given for " + std::to_string(options.limb_goals.size()) +
                           " frames, the source has " + std::to_string(nf));
    }
    for (const Eigen::Matrix3Xd& g : options.limb_goals) {
      if (g.cols() != static_cast<int>(options.solve.limbs.size()) || !g.allFinite()) {
        return Status::Error("retarget: limb goals do not match the limbs or are not finite");
      }
    }
  }
  return Status::Ok();
}

}  // namespace

std::vector<int> FootTrackedVertices(const Skeleton& target_skeleton, const SkinnedMesh& target_mesh,
                                     const RetargetSetup& setup) {
  std::vector<int> feet;
  for (size_t s = 0; s < setup.tracked.size(); ++s) {
    const int v = setup.tracked[s].target_vertex;
    double weight = 0.0;
    for (int k = target_mesh.weight_begin(v); k < target_mesh.weight_end(v); ++k) {
      if (IsFootName(target_skeleton.name(target_mesh.weight_joint(k)))) weight += target_mesh.weight(k);
    }
    if (weight >= 0.5) feet.push_back(static_cast<int>(s));
  }
  return feet;
}

Pose RecenteredStartPose(const Skeleton& target_skeleton, const SkinnedMesh& target_mesh,
                         const RetargetSetup& setup, const Eigen::Matrix3Xd& goal_positions,
                         Pose start) {
  FkData fk(target_skeleton);
  ForwardKinematics(target_skeleton, start, &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(target_mesh, fk, &transforms);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const TrackedVertex& t : setup.tracked) centroid += SkinPosition(target_mesh, transforms, t.target_vertex);
  centroid /= static_cast<double>(std::max<size_t>(1, setup.tracked.size()));
  start.translations[0] += goal_positions.rowwise().mean() - centroid;
  return start;
}

Status RetargetClip(const Skeleton& source_skeleton, const SkinnedMesh& source_mesh,
                    const Motion& source_motion, const Skeleton& target_skeleton,
                    const SkinnedMesh& target_mesh, const RetargetSetup& setup,
                    const RetargetClipOptions& options, RetargetClipResult* result,
                    const RetargetProgressCallback& progress) {
  std::string error;
  if (!options.solve.IsValid(&error)) return Status::Error("retarget: " + error);
  if (source_motion.num_frames() == 0) return Status::Error("retarget: the source animation has no frames");
  if (setup.tracked.empty()) return Status::Error("retarget: no tracked vertices");
  // The goals are made frame by frame as the loop reaches them (a long clip's goals would
  // be 2 x 3 x #tracked doubles per frame); sigma, over the whole clip, first.
  RetargetGoalFrames goal_frames(setup, source_skeleton, source_mesh);
  RetargetClipResult out;
  if (!goal_frames.Sigma(source_motion, &out.sigma)) {
    return Status::Error("retarget: the source animation gives non-finite vertices");
  }
  out.motion.frame_rate = source_motion.frame_rate;
  const int nf = source_motion.num_frames();
  const double height = setup.target_frame.height;

  Pose pose = options.start_pose.rotations.empty() ? RestPose(target_skeleton) : options.start_pose;
  const Status checked = CheckClipInputs(target_skeleton, options, pose, nf);
  if (!checked.ok()) return checked;
  const bool warm_started = !options.warm_start.frames.empty();
  Eigen::Matrix3Xd goal_positions, goal_normals;
  goal_frames.Frame(source_motion.frames[0], &goal_positions, &goal_normals);
  if (!warm_started) pose = RecenteredStartPose(target_skeleton, target_mesh, setup, goal_positions, pose);
  const int np = static_cast<int>(options.solve.plant_joints.size());
  const bool limbs_on = options.solve.limb_direction_weight > 0.0 && !options.solve.limbs.empty();
  Eigen::Matrix3Xd anchors = Eigen::Matrix3Xd::Zero(3, np);
  std::vector<char> anchored(np, 0), active(np, 0);
  FkData plant_fk(target_skeleton);
  FootSkatingSums skating(target_skeleton, target_mesh, setup, FootTrackedVertices(target_skeleton, target_mesh, setup),
                          options.contact_height, source_motion.frame_rate);
  RetargetFrameSolver solver(target_skeleton, target_mesh, setup, out.sigma, options.solve);
  out.motion.frames.reserve(nf);
  out.frames.reserve(nf);
  const auto start = std::chrono::steady_clock::now();
  for (int f = 0; f < nf; ++f) {
    if (f > 0) goal_frames.Frame(source_motion.frames[f], &goal_positions, &goal_normals);
    RetargetFrameReport report;
    bool anchor_needed = false;
    for (int p = 0; p < np; ++p) {
      if (!options.plant_contacts[p][f]) anchored[p] = 0;
      active[p] = anchored[p];
      anchor_needed |= options.plant_contacts[p][f] && !anchored[p];
    }
    if (np > 0) solver.SetPlants(anchors, active);
    if (limbs_on) solver.SetLimbGoals(options.limb_goals[f]);
    if (warm_started) pose = options.warm_start.frames[f];
    const int solves = !options.run_solver ? 0 : f == 0 ? std::max(1, options.first_frame_solves) : 1;
    for (int repeat = 0; repeat < solves; ++repeat) {
      const Status status = solver.Solve(goal_positions, goal_normals, &pose, &report);
      if (!status.ok()) return Status::Error(status.message() + " (frame " + std::to_string(f) + ")");
    }
    if (solves == 0) {
      TrackedVertexErrors(target_skeleton, target_mesh, setup, pose, goal_positions, goal_normals,
                          &report.mean_position_error, &report.mean_normal_angle, &report.mean_effector_error);
    }
    if (anchor_needed) {
      ForwardKinematics(target_skeleton, pose, &plant_fk);
      for (int p = 0; p < np; ++p) {
        if (options.plant_contacts[p][f] && !anchored[p]) {
          anchors.col(p) = plant_fk.world_positions[options.solve.plant_joints[p]];
          anchors(1, p) = std::max(anchors(1, p), LowestHeight(options.solve, options.solve.plant_joints[p]));
          anchored[p] = 1;
        }
      }
    }
    out.motion.frames.push_back(pose);
    RetargetFrameFigures figures;
    figures.position_error = report.mean_position_error / height;
    figures.normal_error_deg = RadToDeg(report.mean_normal_angle);
    figures.effector_error = report.mean_effector_error / height;
    figures.final_cost = report.final_cost;
    figures.iterations = report.iterations;
    out.frames.push_back(figures);
    if (skating.active()) skating.Add(goal_positions, pose);
    if (progress) progress(f + 1, nf);
  }
  out.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.stages = solver.stage_times();
  for (const RetargetFrameFigures& figures : out.frames) {
    out.mean_position_error += figures.position_error / nf;
    out.mean_normal_error_deg += figures.normal_error_deg / nf;
    out.mean_effector_error += figures.effector_error / nf;
    out.mean_final_cost += figures.final_cost / nf;
    out.max_position_error = std::max(out.max_position_error, figures.position_error);
  }
  // Foot skating of the source (goals) and of the result (skinned tracked vertices).
  out.foot_vertices = static_cast<int>(FootTrackedVertices(target_skeleton, target_mesh, setup).size());
  out.contact_pairs = skating.pairs();
  out.source_foot_skating = skating.source();
  out.result_foot_skating = skating.result();
  *result = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
