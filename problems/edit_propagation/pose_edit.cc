#include "problems/edit_propagation/pose_edit.h"

#include <cmath>
#include <string>

#include "kinematics/rotation.h"

namespace mocapsolve {

Eigen::Vector3d UnfoldedLog(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d xyz = q.vec();
  const double n = xyz.norm();
  if (n < 1e-8) {
    // Near the identity: 2 atan2(n, w) / n = (2 / w)(1 - n^2 / (3 w^2) + ...). Near q = -1
    // the axis is undefined; fold (the only discontinuity of the unfolded log).
    if (q.w() <= 0.0) return LogMap(q);
    return 2.0 / q.w() * (1.0 - n * n / (3.0 * q.w() * q.w())) * xyz;
  }
  return (2.0 * std::atan2(n, q.w()) / n) * xyz;
}

Status MakeEdit(const Motion& motion, const PoseOffsets& offsets, PoseEdit* edit) {
  if (offsets.frame < 0 || offsets.frame >= motion.num_frames()) {
    return Status::Error("edit frame " + std::to_string(offsets.frame) + " is outside the motion's " +
                         std::to_string(motion.num_frames()) + " frames");
  }
  PoseEdit result;
  result.frame = offsets.frame;
  result.edited = motion.frames[offsets.frame];
  const int num_joints = static_cast<int>(result.edited.rotations.size());
  for (const auto& [joint, offset] : offsets.rotation_offsets) {
    if (joint < 0 || joint >= num_joints) {
      return Status::Error("edit joint index " + std::to_string(joint) + " out of range");
    }
    if (!offset.allFinite()) return Status::Error("non-finite rotation offset");
    result.edited.rotations[joint] = (result.edited.rotations[joint] * ExpMap(offset)).normalized();
  }
  if (!offsets.root_translation_offset.allFinite()) {
    return Status::Error("non-finite root translation offset");
  }
  if (num_joints > 0) result.edited.translations[0] += offsets.root_translation_offset;
  *edit = std::move(result);
  return Status::Ok();
}

Status PropagateEdits(const Skeleton& skeleton, const Motion& motion,
                      const std::vector<PoseEdit>& edits,
                      const std::vector<Eigen::VectorXd>& weights, Motion* out,
                      std::vector<EditDeltas>* deltas) {
  const int num_joints = skeleton.num_joints();
  const int num_frames = motion.num_frames();
  if (weights.size() != edits.size()) {
    return Status::Error(std::to_string(edits.size()) + " edits but " +
                         std::to_string(weights.size()) + " weight fields");
  }
  std::vector<bool> edited_frame(num_frames, false);
  for (size_t k = 0; k < edits.size(); ++k) {
    const PoseEdit& edit = edits[k];
    if (edit.frame < 0 || edit.frame >= num_frames) {
      return Status::Error("edit frame " + std::to_string(edit.frame) + " is outside the motion's " +
                           std::to_string(num_frames) + " frames");
    }
    if (edited_frame[edit.frame]) {
      return Status::Error("frame " + std::to_string(edit.frame) + " is edited twice");
    }
    edited_frame[edit.frame] = true;
    if (static_cast<int>(edit.edited.rotations.size()) != num_joints ||
        static_cast<int>(edit.edited.translations.size()) != num_joints) {
      return Status::Error("edit of frame " + std::to_string(edit.frame) +
                           ": pose size differs from the skeleton");
    }
    if (weights[k].size() != num_frames || !weights[k].allFinite()) {
      return Status::Error("weights of the edit of frame " + std::to_string(edit.frame) +
                           ": expected " + std::to_string(num_frames) + " finite values");
    }
  }
  Status status = ValidateMotion(skeleton, motion);
  if (!status.ok()) return status;

  Motion result = motion;
  if (deltas != nullptr) {
    deltas->assign(edits.size(), EditDeltas{std::vector<Eigen::Vector3d>(num_joints),
                                            std::vector<Eigen::Vector3d>(num_joints)});
  }
  std::vector<Eigen::Quaterniond> series(num_frames);
  std::vector<Eigen::Vector3d> logs(num_frames);
  for (int j = 0; j < num_joints; ++j) {
    // Rotations: the sign-continuous series, as a whole in the hemisphere of mean w >= 0.
    double sum_w = 0.0;
    for (int f = 0; f < num_frames; ++f) series[f] = motion.frames[f].rotations[j].normalized();
    MakeSignContinuous(&series);
    for (int f = 0; f < num_frames; ++f) sum_w += series[f].w();
    for (int f = 0; f < num_frames; ++f) {
      if (sum_w < 0.0) series[f].coeffs() = -series[f].coeffs();
      logs[f] = UnfoldedLog(series[f]);
    }
    for (size_t k = 0; k < edits.size(); ++k) {
      const int i = edits[k].frame;
      Eigen::Quaterniond edited = edits[k].edited.rotations[j].normalized();
      if (edited.coeffs().dot(series[i].coeffs()) < 0.0) edited.coeffs() = -edited.coeffs();
      const Eigen::Vector3d delta = UnfoldedLog(edited) - logs[i];
      const Eigen::Vector3d translation_delta =
          edits[k].edited.translations[j] - motion.frames[i].translations[j];
      if (deltas != nullptr) {
        (*deltas)[k].rotation[j] = delta;
        (*deltas)[k].translation[j] = translation_delta;
      }
      if (delta.squaredNorm() == 0.0 && translation_delta.squaredNorm() == 0.0) continue;
      for (int f = 0; f < num_frames; ++f) {
        logs[f] += weights[k][f] * delta;
        result.frames[f].translations[j] += weights[k][f] * translation_delta;
      }
    }
    for (int f = 0; f < num_frames; ++f) result.frames[f].rotations[j] = ExpMap(logs[f]);
  }
  *out = std::move(result);
  return Status::Ok();
}

}  // namespace mocapsolve
