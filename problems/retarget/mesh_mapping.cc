#include "problems/retarget/mesh_mapping.h"

#include <glog/logging.h>
#include <nanoflann.hpp>

namespace mocapsolve {
namespace {

using KdTree =
    nanoflann::KDTreeEigenMatrixAdaptor<Eigen::Matrix3Xd, 3, nanoflann::metric_L2_Simple, false>;

}  // namespace

CharacterFrame ComputeCharacterFrame(const Eigen::Matrix3Xd& rest_positions) {
  CHECK_GT(rest_positions.cols(), 0);
  CharacterFrame frame;
  const Eigen::Vector3d mean = rest_positions.rowwise().mean();
  const double min_y = rest_positions.row(1).minCoeff();
  const double max_y = rest_positions.row(1).maxCoeff();
  frame.origin = Eigen::Vector3d(mean.x(), min_y, mean.z());
  frame.height = max_y - min_y > 0.0 ? max_y - min_y : 1.0;
  return frame;
}

std::vector<int> MapToNearestVertices(const Eigen::Matrix3Xd& source_samples,
                                      const CharacterFrame& source_frame,
                                      const Eigen::Matrix3Xd& target_rest,
                                      const CharacterFrame& target_frame) {
  CHECK_GT(target_rest.cols(), 0);
  const Eigen::Matrix3Xd target =
      (target_rest.colwise() - target_frame.origin) / target_frame.height;
  KdTree tree(3, std::cref(target), 10);
  std::vector<int> mapping(source_samples.cols());
  for (int s = 0; s < source_samples.cols(); ++s) {
    const Eigen::Vector3d u = (source_samples.col(s) - source_frame.origin) / source_frame.height;
    Eigen::Index index = 0;
    double distance = 0.0;
    tree.index->knnSearch(u.data(), 1, &index, &distance);
    mapping[s] = static_cast<int>(index);
  }
  return mapping;
}

}  // namespace mocapsolve
