#include "problems/retarget/retarget_clip.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <string>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "kinematics/skinning.h"

namespace mocapsolve {
namespace {

bool IsFootName(std::string name) {
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name.find("foot") != std::string::npos || name.find("toe") != std::string::npos;
}

// Mean horizontal speed of the vertices while the source's are in contact (see the
// header): `contact_positions` decide contact, `positions` give the speed.
double FootSkating(const std::vector<Eigen::Matrix3Xd>& contact_positions,
                   const std::vector<Eigen::Matrix3Xd>& positions, const std::vector<int>& feet,
                   double floor_y, double contact, double height, double frame_rate, int* pairs) {
  double sum = 0.0;
  int count = 0;
  for (size_t f = 1; f < positions.size(); ++f) {
    for (int s : feet) {
      if (contact_positions[f - 1](1, s) - floor_y >= contact ||
          contact_positions[f](1, s) - floor_y >= contact) {
        continue;
      }
      const Eigen::Vector3d a = positions[f - 1].col(s), b = positions[f].col(s);
      sum += std::hypot(b.x() - a.x(), b.z() - a.z()) * frame_rate / height;
      ++count;
    }
  }
  *pairs = count;
  return count > 0 ? sum / count : 0.0;
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
  RetargetGoals goals;
  ComputeRetargetGoals(setup, source_skeleton, source_mesh, source_motion, &goals);
  for (const Eigen::Matrix3Xd& g : goals.positions) {
    if (!g.allFinite()) return Status::Error("retarget: the source animation gives non-finite vertices");
  }
  RetargetClipResult out;
  out.sigma = goals.sigma;
  out.motion.frame_rate = source_motion.frame_rate;
  const int nf = source_motion.num_frames();
  const double height = setup.target_frame.height;

  Pose pose = options.start_pose.rotations.empty() ? RestPose(target_skeleton) : options.start_pose;
  if (static_cast<int>(pose.rotations.size()) != target_skeleton.num_joints() ||
      pose.translations.size() != pose.rotations.size()) {
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
  } else {
    pose = RecenteredStartPose(target_skeleton, target_mesh, setup, goals.positions[0], pose);
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
  Eigen::Matrix3Xd anchors = Eigen::Matrix3Xd::Zero(3, np);
  std::vector<char> anchored(np, 0), active(np, 0);
  FkData plant_fk(target_skeleton);
  RetargetFrameSolver solver(target_skeleton, target_mesh, setup, goals.sigma, options.solve);
  const auto start = std::chrono::steady_clock::now();
  for (int f = 0; f < nf; ++f) {
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
      const Status status = solver.Solve(goals.positions[f], goals.normals[f], &pose, &report);
      if (!status.ok()) return Status::Error(status.message() + " (frame " + std::to_string(f) + ")");
    }
    if (solves == 0) {
      TrackedVertexErrors(target_skeleton, target_mesh, setup, pose, goals.positions[f], goals.normals[f],
                          &report.mean_position_error, &report.mean_normal_angle, &report.mean_effector_error);
    }
    if (anchor_needed) {
      ForwardKinematics(target_skeleton, pose, &plant_fk);
      for (int p = 0; p < np; ++p) {
        if (options.plant_contacts[p][f] && !anchored[p]) {
          anchors.col(p) = plant_fk.world_positions[options.solve.plant_joints[p]];
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
  const std::vector<int> feet = FootTrackedVertices(target_skeleton, target_mesh, setup);
  out.foot_vertices = static_cast<int>(feet.size());
  if (!feet.empty() && source_motion.frame_rate > 0.0) {
    std::vector<Eigen::Matrix3Xd> skinned(nf, Eigen::Matrix3Xd(3, setup.tracked.size()));
    FkData fk(target_skeleton);
    std::vector<Eigen::Isometry3d> transforms;
    for (int f = 0; f < nf; ++f) {
      ForwardKinematics(target_skeleton, out.motion.frames[f], &fk);
      ComputeSkinningTransforms(target_mesh, fk, &transforms);
      for (size_t s = 0; s < setup.tracked.size(); ++s) {
        skinned[f].col(s) = SkinPosition(target_mesh, transforms, setup.tracked[s].target_vertex);
      }
    }
    const double floor_y = setup.target_frame.origin.y();
    const double contact = options.contact_height * height;
    out.source_foot_skating = FootSkating(goals.positions, goals.positions, feet, floor_y, contact,
                                          height, source_motion.frame_rate, &out.contact_pairs);
    out.result_foot_skating = FootSkating(goals.positions, skinned, feet, floor_y, contact, height,
                                          source_motion.frame_rate, &out.contact_pairs);
  }
  *result = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
