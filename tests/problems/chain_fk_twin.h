// The autodiff twins' forward kinematics: a joint-space residual's parameter blocks
// [root translation (3), the rotation of each joint of `chain` (4, x y z w, normalised
// here)] to the world position of the chain's last joint, templated for ceres' Jets.
// `chain` lists the root first and each joint after its parent, as the residuals read them.
#ifndef MOCAPSOLVE_TESTS_PROBLEMS_CHAIN_FK_TWIN_H_
#define MOCAPSOLVE_TESTS_PROBLEMS_CHAIN_FK_TWIN_H_

#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/skeleton.h"

namespace mocapsolve::testing {

template <typename T>
Eigen::Matrix<T, 3, 1> ChainEndPosition(const Skeleton& skeleton, const std::vector<int>& chain,
                                        T const* const* parameters) {
  using std::sqrt;
  std::vector<Eigen::Quaternion<T>> rotation(skeleton.num_joints());
  std::vector<Eigen::Matrix<T, 3, 1>> position(skeleton.num_joints());
  for (size_t s = 0; s < chain.size(); ++s) {
    const int j = chain[s];
    const T* p = parameters[1 + s];
    const T norm = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
    const Eigen::Quaternion<T> local = skeleton.rest_rotation(j).cast<T>() *
                                       Eigen::Quaternion<T>(p[3] / norm, p[0] / norm, p[1] / norm, p[2] / norm);
    if (j == 0) {
      position[0] = Eigen::Matrix<T, 3, 1>(parameters[0][0], parameters[0][1], parameters[0][2]);
      rotation[0] = local;
    } else {
      const int parent = skeleton.parent(j);
      position[j] = position[parent] + rotation[parent] * skeleton.offset(j).cast<T>();
      rotation[j] = rotation[parent] * local;
    }
  }
  return position[chain.back()];
}

}  // namespace mocapsolve::testing

#endif  // MOCAPSOLVE_TESTS_PROBLEMS_CHAIN_FK_TWIN_H_
