#include "solvers/right_quaternion_manifold.h"

#include <cmath>

#include <Eigen/Geometry>

#include "kinematics/rotation.h"

namespace mocapsolve {

bool RightQuaternionManifold::Plus(const double* x, const double* delta,
                                   double* x_plus_delta) const {
  const Eigen::Map<const Eigen::Quaterniond> q(x);
  Eigen::Map<Eigen::Quaterniond> out(x_plus_delta);
  out = (q * ExpMap(Eigen::Map<const Eigen::Vector3d>(delta))).normalized();
  return true;
}

bool RightQuaternionManifold::PlusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 4, 3, Eigen::RowMajor>> out(jacobian);
  out = QuaternionPlusJacobian(x);
  return true;
}

bool RightQuaternionManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  // The manifold is the unit 3-sphere, not SO(3): keep the sign of w (no shortest-path
  // flip as in LogMap), so that Plus(x, Minus(y, x)) = y exactly, also for y.dot(x) < 0.
  const Eigen::Map<const Eigen::Quaterniond> qy(y), qx(x);
  const Eigen::Quaterniond d = qx.conjugate() * qy;
  const double n = d.vec().norm();
  Eigen::Map<Eigen::Vector3d> out(y_minus_x);
  if (d.w() > 0.0 && n < 1e-8) {
    out = LogMap(d);  // Its small-angle branch.
  } else if (n == 0.0) {
    out = Eigen::Vector3d(2.0 * kPi, 0.0, 0.0);  // d = -1: a full turn about any axis.
  } else {
    out = 2.0 * std::atan2(n, d.w()) / n * d.vec();
  }
  return true;
}

bool RightQuaternionManifold::MinusJacobian(const double* x, double* jacobian) const {
  // d log(x^-1 y)/dy at y = x is 2 [x^-1 (x) dy]_vec = 4 P(x)^T for unit x.
  Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> out(jacobian);
  out = AmbientFromTangent(x);
  return true;
}

Eigen::Matrix<double, 4, 3> QuaternionPlusJacobian(const double* q) {
  // Column k: 1/2 q (x) (0, e_k) = 1/2 (w e_k + v x e_k, -v_k) in (x, y, z, w) order.
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  Eigen::Matrix<double, 4, 3> p;
  p << w, -z, y,
       z, w, -x,
       -y, x, w,
       -x, -y, -z;
  return 0.5 * p;
}

Eigen::Matrix<double, 3, 4> AmbientFromTangent(const double* q) {
  return 4.0 * QuaternionPlusJacobian(q).transpose();
}

}  // namespace mocapsolve
