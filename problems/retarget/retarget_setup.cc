#include "problems/retarget/retarget_setup.h"

#include <algorithm>
#include <cctype>
#include <cmath>


#include "kinematics/forward_kinematics.h"
#include "kinematics/skinning.h"

namespace mocapsolve {
namespace {

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

void BindPoseMesh(const SkinnedMesh& mesh, const Eigen::Matrix3d& world_from_bind,
                  Eigen::Matrix3Xd* positions, Eigen::Matrix3Xd* normals) {
  *positions = world_from_bind * mesh.rest_positions();
  if (normals == nullptr) return;
  *normals = world_from_bind * mesh.rest_normals();
  for (int i = 0; i < normals->cols(); ++i) {
    const double norm = normals->col(i).norm();
    if (norm > 0.0) normals->col(i) /= norm;
  }
}

Eigen::Matrix3d WorldFromBindRotation(const Skeleton& skeleton, const Pose& bind_pose,
                                      const Pose& world_pose) {
  FkData bind(skeleton), world(skeleton);
  ForwardKinematics(skeleton, bind_pose, &bind);
  ForwardKinematics(skeleton, world_pose, &world);
  return (world.world_rotations[0] * bind.world_rotations[0].conjugate()).toRotationMatrix();
}

Status BuildRetargetSetup(const SkinnedMesh& source_mesh, const Skeleton& target_skeleton,
                          const SkinnedMesh& target_mesh,
                          const RetargetSetupOptions& options, RetargetSetup* setup) {
  if (source_mesh.num_vertices() == 0 || target_mesh.num_vertices() == 0) {
    return Status::Error("retarget: a mesh has no vertices");
  }
  if (!source_mesh.has_normals()) return Status::Error("retarget: the source mesh has no normals");
  if (!target_mesh.has_normals()) return Status::Error("retarget: the target mesh has no normals");
  if (options.same_vertices && source_mesh.num_vertices() != target_mesh.num_vertices()) {
    return Status::Error("retarget: the source mesh is not the target's (" +
                         std::to_string(source_mesh.num_vertices()) + " vertices, target " +
                         std::to_string(target_mesh.num_vertices()) + ")");
  }
  const int num_parts = static_cast<int>(options.source_parts.size());
  if (num_parts > 0 && num_parts != source_mesh.num_vertices()) {
    return Status::Error("retarget: source parts for " + std::to_string(num_parts) + " vertices, mesh has " +
                         std::to_string(source_mesh.num_vertices()));
  }
  if (options.subsample.ratio < 1) {
    return Status::Error("retarget: subsample ratio must be >= 1, got " +
                         std::to_string(options.subsample.ratio));
  }
  RetargetSetup result;
  // Position joints.
  if (!options.position_joints.empty()) {
    for (const std::string& name : options.position_joints) {
      const int j = target_skeleton.FindJoint(name);
      if (j < 0) return Status::Error("blend mask: no joint '" + name + "' in the target skeleton");
      result.position_joints.push_back(j);
    }
  } else {
    for (int j = 0; j < target_skeleton.num_joints(); ++j) {
      const std::string name = Lower(target_skeleton.name(j));
      for (const std::string& pattern : options.position_name_patterns) {
        if (name.find(Lower(pattern)) != std::string::npos) {
          result.position_joints.push_back(j);
          break;
        }
      }
    }
    if (result.position_joints.empty()) {
      std::vector<bool> dominates(target_skeleton.num_joints(), false), has_child(target_skeleton.num_joints(), false);
      for (int v = 0; v < target_mesh.num_vertices(); ++v) dominates[DominantJoint(target_mesh, v)] = true;
      for (int j = 1; j < target_skeleton.num_joints(); ++j) has_child[target_skeleton.parent(j)] = true;
      std::vector<bool> chosen(target_skeleton.num_joints(), false);
      for (int j = 0; j < target_skeleton.num_joints(); ++j) {
        if (has_child[j]) continue;
        int a = j;
        while (a > 0 && !dominates[a]) a = target_skeleton.parent(a);
        if (a > 0 && !chosen[a]) {
          chosen[a] = true;
          result.position_joints.push_back(a);
        }
      }
      std::string names;
      for (int j : result.position_joints) names += (names.empty() ? "" : ", ") + target_skeleton.name(j);
      result.notes.push_back("blend mask: no target joint named like a hand, foot, toe or head; "
                             "tracking the ends of the chains by position: " + names);
      if (result.position_joints.empty()) result.notes.push_back("blend mask: every sample tracks its position");
    }
  }

  Eigen::Matrix3Xd source_rest, source_normals, target_rest, target_normals;
  BindPoseMesh(source_mesh, options.source_world_from_bind, &source_rest, &source_normals);
  BindPoseMesh(target_mesh, options.target_world_from_bind, &target_rest, &target_normals);
  result.source_frame = ComputeCharacterFrame(source_rest, true, options.source_left);
  result.target_frame = ComputeCharacterFrame(target_rest, true, options.target_left);
  result.scale = result.target_frame.height / result.source_frame.height;

  const std::vector<int> samples =
      SubsampleVertices(source_mesh, source_rest, source_normals, options.subsample, options.source_parts);
  Eigen::Matrix3Xd sample_rest(3, samples.size()), sample_normals(3, samples.size());
  for (size_t s = 0; s < samples.size(); ++s) {
    sample_rest.col(s) = source_rest.col(samples[s]);
    sample_normals.col(s) = source_normals.col(samples[s]);
  }
  const std::vector<int> mapping =
      options.same_vertices ? samples
                            : MapToNearestVertices(sample_rest, result.source_frame, target_rest, result.target_frame,
                                                   sample_normals, target_normals, options.mapping_normal_weight);
  // Target world -> source bind space, for transferred normals.
  const Eigen::Matrix3d source_bind_from_target_world =
      options.source_world_from_bind.transpose() * result.source_frame.facing.transpose() *
      result.target_frame.facing;

  for (size_t s = 0; s < samples.size(); ++s) {
    TrackedVertex tracked;
    tracked.source_vertex = samples[s];
    tracked.target_vertex = mapping[s];
    tracked.rest_normal =
        options.transfer_normals
            ? Eigen::Vector3d(source_bind_from_target_world * target_normals.col(mapping[s]))
            : Eigen::Vector3d(source_mesh.rest_normals().col(samples[s]).normalized());
    if (result.position_joints.empty()) {
      tracked.track_position = true;
    } else {
      // Cumulative weight on the union of the position joints' subtrees.
      double weight = 0.0;
      const int v = tracked.target_vertex;
      for (int k = target_mesh.weight_begin(v); k < target_mesh.weight_end(v); ++k) {
        const int b = target_mesh.weight_joint(k);
        for (int j : result.position_joints) {
          if (target_skeleton.IsAncestorOrSelf(j, b)) {
            weight += target_mesh.weight(k);
            break;
          }
        }
      }
      tracked.track_position = weight >= options.position_weight_threshold;
    }
    result.tracked.push_back(tracked);
  }
  *setup = std::move(result);
  return Status::Ok();
}

RetargetGoalFrames::RetargetGoalFrames(const RetargetSetup& setup, const Skeleton& source_skeleton,
                                       const SkinnedMesh& source_mesh)
    : setup_(setup),
      skeleton_(source_skeleton),
      mesh_(source_mesh),
      turn_(setup.target_frame.facing.transpose() * setup.source_frame.facing),
      fk_(source_skeleton) {}

void RetargetGoalFrames::Frame(const Pose& source_pose, Eigen::Matrix3Xd* positions, Eigen::Matrix3Xd* normals) {
  const int nt = static_cast<int>(setup_.tracked.size());
  positions->resize(3, nt);
  if (normals != nullptr) normals->resize(3, nt);
  ForwardKinematics(skeleton_, source_pose, &fk_);
  ComputeSkinningTransforms(mesh_, fk_, &transforms_);
  for (int s = 0; s < nt; ++s) {
    const int v = setup_.tracked[s].source_vertex;
    positions->col(s) = setup_.target_frame.origin +
                        setup_.scale * (turn_ * (SkinPosition(mesh_, transforms_, v) - setup_.source_frame.origin));
    if (normals == nullptr) continue;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (int k = mesh_.weight_begin(v); k < mesh_.weight_end(v); ++k) {
      normal += mesh_.weight(k) * (transforms_[mesh_.weight_joint(k)].linear() * setup_.tracked[s].rest_normal);
    }
    normals->col(s) = turn_ * normal;
  }
}

namespace {

// sqrt(sum |g - mean|^2 / (3 N)) from the sum of the goals and the sum of squares about
// the mean; the target height when the goals do not spread.
double GoalSigma(double squares, double count, double height) {
  const double sigma = count > 0 ? std::sqrt(squares / (3.0 * count)) : 0.0;
  return sigma > 0.0 ? sigma : height;
}

}  // namespace

bool RetargetGoalFrames::Sigma(const Motion& source_motion, double* sigma) {
  const int nf = source_motion.num_frames();
  const double count = static_cast<double>(nf) * setup_.tracked.size();
  Eigen::Matrix3Xd positions;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int f = 0; f < nf; ++f) {
    Frame(source_motion.frames[f], &positions, nullptr);
    if (!positions.allFinite()) return false;
    for (Eigen::Index s = 0; s < positions.cols(); ++s) sum += positions.col(s);
  }
  double squares = 0.0;
  if (count > 0) {
    const Eigen::Vector3d mean = sum / count;
    for (int f = 0; f < nf; ++f) {
      Frame(source_motion.frames[f], &positions, nullptr);
      squares += (positions.colwise() - mean).squaredNorm();
    }
  }
  *sigma = GoalSigma(squares, count, setup_.target_frame.height);
  return true;
}

void ComputeRetargetGoals(const RetargetSetup& setup, const Skeleton& source_skeleton,
                          const SkinnedMesh& source_mesh, const Motion& source_motion,
                          RetargetGoals* goals) {
  const int nf = source_motion.num_frames();
  goals->positions.resize(nf);
  goals->normals.resize(nf);
  RetargetGoalFrames frames(setup, source_skeleton, source_mesh);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int f = 0; f < nf; ++f) {
    frames.Frame(source_motion.frames[f], &goals->positions[f], &goals->normals[f]);
    for (Eigen::Index s = 0; s < goals->positions[f].cols(); ++s) sum += goals->positions[f].col(s);
  }
  const double count = static_cast<double>(nf) * setup.tracked.size();
  double squares = 0.0;
  if (count > 0) {
    const Eigen::Vector3d mean = sum / count;
    for (int f = 0; f < nf; ++f) squares += (goals->positions[f].colwise() - mean).squaredNorm();
  }
  goals->sigma = GoalSigma(squares, count, setup.target_frame.height);
}

}  // namespace mocapsolve
