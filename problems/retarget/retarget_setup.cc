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

void BindPoseMesh(const SkinnedMesh& mesh, Eigen::Matrix3Xd* positions, Eigen::Matrix3Xd* normals) {
  *positions = mesh.rest_positions();
  if (normals == nullptr) return;
  *normals = mesh.rest_normals();
  for (int i = 0; i < normals->cols(); ++i) {
    const double norm = normals->col(i).norm();
    if (norm > 0.0) normals->col(i) /= norm;
  }
}

Status BuildRetargetSetup(const SkinnedMesh& source_mesh, const Skeleton& target_skeleton,
                          const SkinnedMesh& target_mesh,
                          const RetargetSetupOptions& options, RetargetSetup* setup) {
  if (source_mesh.num_vertices() == 0 || target_mesh.num_vertices() == 0) {
    return Status::Error("retarget: a mesh has no vertices");
  }
  if (!source_mesh.has_normals()) return Status::Error("retarget: the source mesh has no normals");
  if (!target_mesh.has_normals()) return Status::Error("retarget: the target mesh has no normals");
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
      result.notes.push_back(
          "blend mask: no target joint named like a hand, foot, toe or head; every sample tracks "
          "its position");
    }
  }

  Eigen::Matrix3Xd source_rest, source_normals, target_rest;
  BindPoseMesh(source_mesh, &source_rest, &source_normals);
  BindPoseMesh(target_mesh, &target_rest, nullptr);
  result.source_frame = ComputeCharacterFrame(source_rest);
  result.target_frame = ComputeCharacterFrame(target_rest);
  result.scale = result.target_frame.height / result.source_frame.height;

  const std::vector<int> samples =
      SubsampleVertices(source_mesh, source_rest, source_normals, options.subsample);
  Eigen::Matrix3Xd sample_rest(3, samples.size());
  for (size_t s = 0; s < samples.size(); ++s) sample_rest.col(s) = source_rest.col(samples[s]);
  const std::vector<int> mapping =
      MapToNearestVertices(sample_rest, result.source_frame, target_rest, result.target_frame);

  for (size_t s = 0; s < samples.size(); ++s) {
    TrackedVertex tracked;
    tracked.source_vertex = samples[s];
    tracked.target_vertex = mapping[s];
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

void ComputeRetargetGoals(const RetargetSetup& setup, const Skeleton& source_skeleton,
                          const SkinnedMesh& source_mesh, const Motion& source_motion,
                          RetargetGoals* goals) {
  const int nt = static_cast<int>(setup.tracked.size());
  const int nf = source_motion.num_frames();
  goals->positions.assign(nf, Eigen::Matrix3Xd(3, nt));
  goals->normals.assign(nf, Eigen::Matrix3Xd(3, nt));
  FkData fk(source_skeleton);
  std::vector<Eigen::Isometry3d> transforms;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int f = 0; f < nf; ++f) {
    ForwardKinematics(source_skeleton, source_motion.frames[f], &fk);
    ComputeSkinningTransforms(source_mesh, fk, &transforms);
    for (int s = 0; s < nt; ++s) {
      const int v = setup.tracked[s].source_vertex;
      goals->positions[f].col(s) =
          setup.target_frame.origin +
          setup.scale * (SkinPosition(source_mesh, transforms, v) - setup.source_frame.origin);
      goals->normals[f].col(s) = SkinNormal(source_mesh, transforms, v);
      sum += goals->positions[f].col(s);
    }
  }
  const double count = static_cast<double>(nf) * nt;
  double squares = 0.0;
  if (count > 0) {
    const Eigen::Vector3d mean = sum / count;
    for (int f = 0; f < nf; ++f) squares += (goals->positions[f].colwise() - mean).squaredNorm();
  }
  const double sigma = count > 0 ? std::sqrt(squares / (3.0 * count)) : 0.0;
  goals->sigma = sigma > 0.0 ? sigma : setup.target_frame.height;
}

}  // namespace mocapsolve
