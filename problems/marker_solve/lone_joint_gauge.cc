#include "problems/marker_solve/lone_joint_gauge.h"

#include <Eigen/Geometry>

#include "problems/marker_solve/mean_pose.h"

namespace mocapsolve {

Status FixLoneJointGauges(const Skeleton& skeleton, MarkerSet* markers, Motion* motion,
                          std::vector<std::string>* labels) {
  labels->clear();
  Status status = ValidateMotion(skeleton, *motion);
  if (!status.ok()) return status;
  if (motion->num_frames() == 0) return Status::Error("lone joint gauge: the motion has no frames");
  const int joints = skeleton.num_joints();
  // Attachments on each joint and on its subtree (parents-first order: children after).
  std::vector<int> own(joints, 0), subtree(joints, 0);
  for (int m = 0; m < markers->num_markers(); ++m) {
    for (const MarkerAttachment& a : markers->marker(m).attachments) ++own[a.joint];
  }
  for (int j = joints - 1; j >= 0; --j) {
    subtree[j] += own[j];
    if (skeleton.parent(j) >= 0) subtree[skeleton.parent(j)] += subtree[j];
  }
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < markers->num_markers(); ++m) specs.push_back(markers->marker(m));
  bool changed = false;
  for (MarkerSpec& spec : specs) {
    if (spec.attachments.size() != 1) continue;
    const int j = spec.attachments[0].joint;
    const int dofs = skeleton.num_rotation_dofs(j);
    if (subtree[j] != 1 || (dofs != 1 && dofs != 3)) continue;
    Eigen::Quaterniond r = MeanLocalRotation(*motion, j);
    if (dofs == 3) {
      // Turned the least so that r z points at the mean of q z (what a prediction at
      // rest should hit); the quaternion mean alone can miss it when q twists about z.
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const Pose& pose : motion->frames) mean += pose.rotations[j] * spec.attachments[0].offset;
      if (mean.norm() > 0.0 && spec.attachments[0].offset.norm() > 0.0) {
        r = (Eigen::Quaterniond::FromTwoVectors(r * spec.attachments[0].offset, mean) * r).normalized();
      }
    }
    spec.attachments[0].offset = r * spec.attachments[0].offset;
    const Eigen::Quaterniond inverse = r.conjugate();
    for (Pose& pose : motion->frames) pose.rotations[j] = (pose.rotations[j] * inverse).normalized();
    labels->push_back(spec.label);
    changed = true;
  }
  if (!changed) return Status::Ok();
  return MarkerSet::Create(skeleton, std::move(specs), markers);
}

}  // namespace mocapsolve
