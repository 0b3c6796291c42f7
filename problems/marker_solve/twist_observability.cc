#include "problems/marker_solve/twist_observability.h"

#include <vector>

#include <Eigen/QR>

#include "kinematics/forward_kinematics.h"

namespace mocapsolve {

double TwistObservability(const Skeleton& skeleton, const MarkerSet& markers, const Pose& pose, int joint,
                          const Eigen::Vector3d& axis_in_joint, const std::vector<bool>* visible) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose, &fk);
  auto below = [&](int j) { return j != joint && skeleton.IsAncestorOrSelf(joint, j); };
  std::vector<int> rows;  // Markers whose attachments all lie strictly below the joint.
  for (int m = 0; m < markers.num_markers(); ++m) {
    if (visible != nullptr && !(*visible)[m]) continue;
    bool all_below = !markers.marker(m).attachments.empty();
    for (const MarkerAttachment& a : markers.marker(m).attachments) all_below = all_below && below(a.joint);
    if (all_below) rows.push_back(m);
  }
  if (rows.empty()) return 0.0;
  std::vector<int> columns;  // (joint, local axis) of every dof below, two ints each.
  for (int c = joint + 1; c < skeleton.num_joints(); ++c) {
    if (!below(c)) continue;
    for (int k : skeleton.rotation_axes(c)) columns.insert(columns.end(), {c, k});
  }
  const int n = static_cast<int>(rows.size());
  Eigen::VectorXd twist = Eigen::VectorXd::Zero(3 * n);
  Eigen::MatrixXd compensation = Eigen::MatrixXd::Zero(3 * n, columns.size() / 2);
  const Eigen::Vector3d a = fk.world_rotations[joint] * axis_in_joint.normalized();
  for (int r = 0; r < n; ++r) {
    for (const MarkerAttachment& at : markers.marker(rows[r]).attachments) {
      const Eigen::Vector3d p = fk.world_positions[at.joint] + fk.world_rotations[at.joint] * at.offset;
      twist.segment<3>(3 * r) += at.weight * a.cross(p - fk.world_positions[joint]);
      for (size_t col = 0; col < columns.size() / 2; ++col) {
        const int c = columns[2 * col];
        if (!skeleton.IsAncestorOrSelf(c, at.joint)) continue;
        const Eigen::Vector3d axis = fk.world_rotations[c] * Eigen::Vector3d::Unit(columns[2 * col + 1]);
        compensation.block<3, 1>(3 * r, col) += at.weight * axis.cross(p - fk.world_positions[c]);
      }
    }
  }
  if (compensation.cols() == 0) return twist.norm();
  const Eigen::VectorXd taken = compensation * compensation.colPivHouseholderQr().solve(twist);
  return (twist - taken).norm();
}

}  // namespace mocapsolve
