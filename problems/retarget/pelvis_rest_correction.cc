#include "problems/retarget/pelvis_rest_correction.h"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

namespace mocapsolve {

Eigen::Quaterniond BestRestRotation(const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& v) {
  Eigen::Vector3d mean_u = Eigen::Vector3d::Zero(), mean_v = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < u.size(); ++i) {
    mean_u += u[i];
    mean_v += v[i];
  }
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < u.size(); ++i) h += u[i] * v[i].transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  if (u.size() == 1 || svd.singularValues()(1) < 0.05 * svd.singularValues()(0)) {
    return Eigen::Quaterniond::FromTwoVectors(mean_u, mean_v);
  }
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return Eigen::Quaterniond(Eigen::Matrix3d(svd.matrixV() * d * svd.matrixU().transpose())).normalized();
}

Eigen::Quaterniond BestTurnAboutUp(const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& v) {
  double along = 0.0, across = 0.0;  // sum of u.v and of (u x v).y, horizontal parts only.
  for (size_t i = 0; i < u.size(); ++i) {
    along += u[i].x() * v[i].x() + u[i].z() * v[i].z();
    across += u[i].z() * v[i].x() - u[i].x() * v[i].z();
  }
  if (std::hypot(along, across) < 1e-12) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(std::atan2(across, along), Eigen::Vector3d::UnitY()));
}

PelvisCorrection PelvisRestCorrection(const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& v) {
  PelvisCorrection result;
  if (u.empty()) return result;
  const Eigen::Quaterniond full = BestRestRotation(u, v);
  const Eigen::Quaterniond turn = BestTurnAboutUp(u, v);
  double sum = 0.0;
  for (size_t i = 0; i < u.size(); ++i) {
    const Eigen::Vector3d a = full * u[i];
    sum += std::pow(std::atan2(a.cross(v[i]).norm(), a.dot(v[i])) * 180.0 / M_PI, 2);
  }
  result.residual_deg = std::sqrt(sum / u.size());
  result.tilt_kept = u.size() < 3 ? 0.0
                                  : std::clamp((kPelvisDisagreeDeg - result.residual_deg) /
                                                   (kPelvisDisagreeDeg - kPelvisAgreeDeg),
                                               0.0, 1.0);
  result.rotation = turn.slerp(result.tilt_kept, full).normalized();
  return result;
}

}  // namespace mocapsolve
