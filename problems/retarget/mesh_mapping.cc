#include "problems/retarget/mesh_mapping.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <glog/logging.h>
#include <nanoflann.hpp>

namespace mocapsolve {
namespace {

using KdTree =
    nanoflann::KDTreeEigenMatrixAdaptor<Eigen::Matrix3Xd, 3, nanoflann::metric_L2_Simple, false>;
using Matrix6Xd = Eigen::Matrix<double, 6, Eigen::Dynamic>;
using KdTree6 = nanoflann::KDTreeEigenMatrixAdaptor<Matrix6Xd, 6, nanoflann::metric_L2_Simple, false>;

}  // namespace

CharacterFrame ComputeCharacterFrame(const Eigen::Matrix3Xd& rest_positions, bool align_facing,
                                     const Eigen::Vector3d& left) {
  CHECK_GT(rest_positions.cols(), 0);
  CharacterFrame frame;
  const Eigen::Vector3d mean = rest_positions.rowwise().mean();
  const double min_y = rest_positions.row(1).minCoeff();
  const double max_y = rest_positions.row(1).maxCoeff();
  frame.origin = Eigen::Vector3d(mean.x(), min_y, mean.z());
  frame.height = max_y - min_y > 0.0 ? max_y - min_y : 1.0;
  if (!align_facing) return frame;
  // Horizontal spread (x, z): its major axis is left-right.
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
  Eigen::Vector2d feet = Eigen::Vector2d::Zero();
  int num_feet = 0;
  for (int i = 0; i < rest_positions.cols(); ++i) {
    const Eigen::Vector2d h(rest_positions(0, i) - mean.x(), rest_positions(2, i) - mean.z());
    spread += h * h.transpose();
    if (rest_positions(1, i) < min_y + 0.05 * frame.height) {
      feet += h;
      ++num_feet;
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(spread);
  const Eigen::Vector2d side = eigen.eigenvectors().col(1);  // Largest eigenvalue.
  Eigen::Vector2d forward(-side.y(), side.x());
  const Eigen::Vector2d left_forward(-left.z(), left.x());  // (left x up) in (x, z).
  if (left_forward.norm() > 1e-9 * frame.height) {
    if (forward.dot(left_forward) < 0.0) forward = -forward;
  } else if (num_feet > 0 && forward.dot(feet / num_feet) < 0.0) {
    forward = -forward;
  }
  // F turns forward (x, z) onto +Z: a rotation about Y by -atan2(forward_x, forward_z).
  const double yaw = std::atan2(forward.x(), forward.y());
  frame.facing = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return frame;
}

std::vector<int> MapToNearestVertices(const Eigen::Matrix3Xd& source_samples,
                                      const CharacterFrame& source_frame,
                                      const Eigen::Matrix3Xd& target_rest,
                                      const CharacterFrame& target_frame,
                                      const Eigen::Matrix3Xd& source_normals,
                                      const Eigen::Matrix3Xd& target_normals,
                                      double normal_weight) {
  CHECK_GT(target_rest.cols(), 0);
  if (normal_weight > 0.0 && source_normals.cols() == source_samples.cols() &&
      target_normals.cols() == target_rest.cols()) {
    Matrix6Xd target(6, target_rest.cols());
    target.topRows<3>() =
        target_frame.facing * (target_rest.colwise() - target_frame.origin) / target_frame.height;
    target.bottomRows<3>() = normal_weight * target_frame.facing * target_normals;
    KdTree6 tree(6, std::cref(target), 10);
    std::vector<int> mapping(source_samples.cols());
    for (int s = 0; s < source_samples.cols(); ++s) {
      Eigen::Matrix<double, 6, 1> u;
      u.head<3>() = source_frame.facing * (source_samples.col(s) - source_frame.origin) / source_frame.height;
      u.tail<3>() = normal_weight * source_frame.facing * source_normals.col(s);
      Eigen::Index index = 0;
      double distance = 0.0;
      tree.index->knnSearch(u.data(), 1, &index, &distance);
      mapping[s] = static_cast<int>(index);
    }
    return mapping;
  }
  const Eigen::Matrix3Xd target =
      target_frame.facing * (target_rest.colwise() - target_frame.origin) / target_frame.height;
  KdTree tree(3, std::cref(target), 10);
  std::vector<int> mapping(source_samples.cols());
  for (int s = 0; s < source_samples.cols(); ++s) {
    const Eigen::Vector3d u =
        source_frame.facing * (source_samples.col(s) - source_frame.origin) / source_frame.height;
    Eigen::Index index = 0;
    double distance = 0.0;
    tree.index->knnSearch(u.data(), 1, &index, &distance);
    mapping[s] = static_cast<int>(index);
  }
  return mapping;
}

}  // namespace mocapsolve
