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

DofQuaternionManifold::DofQuaternionManifold(std::vector<int> axes) : axes_(std::move(axes)) {}

namespace {

// Two axes a0, a1 (c the third, e_a0 x e_a1 = eps e_c): is q's second angle beyond pi/2
// (sin^2(t1/2) = v_a1^2 + v_c^2 above cos^2(t1/2) = w^2 + v_a0^2), where an Euler
// decomposition (middle angle in [-pi/2, pi/2]) reads a point of the set as another one?
bool BeyondHalfTurn(const double* x, int a0, int a1) {
  const int c = 3 - a0 - a1;
  return x[a1] * x[a1] + x[c] * x[c] >= x[3] * x[3] + x[a0] * x[a0] - 1e-9;
}

// There, the angles from the rank-1 factorization of q = Q0(t0) Q1(t1):
//   [w, v_a1; v_a0, eps v_c] = [cos(t0/2); sin(t0/2)] [cos(t1/2), sin(t1/2)],
// exact for any point of the set (no branch, no gimbal lock), each angle then wrapped into
// (-pi, pi] as the Euler path's are: Compose of the angles is q or -q (its w >= 0), so a
// solve's path does not depend on the sign its start was stored with. Off the set, one
// power step of the best rank-1 approximation (from its larger column).
void RankOneAngles(const double* x, int a0, int a1, double* angles) {
  const int c = 3 - a0 - a1;
  const double eps = a1 == (a0 + 1) % 3 ? 1.0 : -1.0;
  const Eigen::Matrix2d m = (Eigen::Matrix2d() << x[3], x[a1], x[a0], eps * x[c]).finished();
  const int k = m.col(0).squaredNorm() >= m.col(1).squaredNorm() ? 0 : 1;
  const Eigen::Vector2d u = m.col(k).normalized();
  const Eigen::Vector2d v = m.transpose() * u;
  angles[0] = std::remainder(2.0 * std::atan2(u[1], u[0]), 2.0 * kPi);
  angles[1] = std::remainder(2.0 * std::atan2(v[1], v[0]), 2.0 * kPi);
}

}  // namespace

void DofQuaternionManifold::Angles(const double* x, double* angles) const {
  if (axes_.size() == 2 && BeyondHalfTurn(x, axes_[0], axes_[1])) {
    double unit[4];
    const double norm = Eigen::Map<const Eigen::Vector4d>(x).norm();
    for (int i = 0; i < 4; ++i) unit[i] = x[i] / norm;
    RankOneAngles(unit, axes_[0], axes_[1], angles);
    return;
  }
  AnglesAboutAxes(Eigen::Quaterniond(Eigen::Map<const Eigen::Quaterniond>(x)), axes_, angles);
}

void DofQuaternionManifold::Compose(const double* angles, double* x) const {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (size_t i = 0; i < axes_.size(); ++i) {
    q = q * Eigen::Quaterniond(Eigen::AngleAxisd(angles[i], Eigen::Vector3d::Unit(axes_[i])));
  }
  Eigen::Map<Eigen::Quaterniond> out(x);
  out = q;
}

bool DofQuaternionManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  double angles[2];
  Angles(x, angles);
  for (size_t i = 0; i < axes_.size(); ++i) angles[i] += delta[i];
  Compose(angles, x_plus_delta);
  return true;
}

bool DofQuaternionManifold::PlusJacobian(const double* x, double* jacobian) const {
  // On the set, q = Q0 Q1: d/dt1 = 1/2 q (x) (0, e_a1) (column a1 of P(q)) and
  // d/dt0 = 1/2 (0, e_a0) (x) q (the left-multiplied twin).
  double angles[2], on_set[4];
  Angles(x, angles);
  Compose(angles, on_set);
  const Eigen::Quaterniond q = Eigen::Map<const Eigen::Quaterniond>(on_set);
  const int k = TangentSize();
  for (int i = 0; i < k; ++i) {
    Eigen::Quaterniond axis(0.0, 0.0, 0.0, 0.0);
    axis.vec()[axes_[i]] = 0.5;
    const Eigen::Quaterniond column = (i == 0 && k == 2) ? axis * q : q * axis;
    for (int r = 0; r < 4; ++r) jacobian[r * k + i] = column.coeffs()[r];
  }
  return true;
}

bool DofQuaternionManifold::PlusJacobianOnSet(const double* x, double* jacobian) const {
  const Eigen::Map<const Eigen::Quaterniond> q(x);
  const int k = TangentSize();
  if (k == 1) {
    const int a = axes_[0];
    if (std::abs(q.vec()[(a + 1) % 3]) + std::abs(q.vec()[(a + 2) % 3]) > 1e-12) return false;
  } else {
    const int a0 = axes_[0], a1 = axes_[1], c = 3 - a0 - a1;
    const double eps = a1 == (a0 + 1) % 3 ? 1.0 : -1.0;  // e_a0 x e_a1 = eps e_c.
    if (std::abs(q.w() * q.vec()[c] - eps * q.vec()[a0] * q.vec()[a1]) > 1e-12) return false;
  }
  // The projection Compose(Angles(q)) has w = prod cos(t_i / 2) >= 0 (angles in (-pi, pi],
  // the Euler path's or, beyond a quarter turn of the second, RankOneAngles'): q or -q.
  if (std::abs(q.w()) <= 1e-12) return false;
  Eigen::Quaterniond on_set = q;
  if (q.w() < 0.0) on_set.coeffs() = -on_set.coeffs();
  for (int i = 0; i < k; ++i) {
    Eigen::Quaterniond axis(0.0, 0.0, 0.0, 0.0);
    axis.vec()[axes_[i]] = 0.5;
    const Eigen::Quaterniond column = (i == 0 && k == 2) ? axis * on_set : on_set * axis;
    for (int r = 0; r < 4; ++r) jacobian[r * k + i] = column.coeffs()[r];
  }
  return true;
}

bool DofQuaternionManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  double ay[2], ax[2];
  Angles(y, ay);
  Angles(x, ax);
  for (size_t i = 0; i < axes_.size(); ++i) y_minus_x[i] = std::remainder(ay[i] - ax[i], 2.0 * kPi);
  return true;
}

bool DofQuaternionManifold::MinusJacobian(const double* x, double* jacobian) const {
  // d Angles(y)/dy at y = x: the angles' rate per local increment times d delta/dy.
  const Eigen::Map<const Eigen::Quaterniond> q(x);
  double angles[3];
  Eigen::Matrix<double, Eigen::Dynamic, 3> rate;
  AnglesAboutAxes(q, axes_, angles, &rate);
  Eigen::Vector4d unit = q.coeffs();
  const double norm = unit.norm();
  unit /= norm;
  const Eigen::Matrix<double, Eigen::Dynamic, 4> d = rate * AmbientFromTangent(unit.data()) / norm;
  for (int r = 0; r < d.rows(); ++r) {
    for (int c = 0; c < 4; ++c) jacobian[r * 4 + c] = d(r, c);
  }
  return true;
}

ceres::Manifold* RotationManifold(const std::vector<int>& axes) {
  static RightQuaternionManifold full;
  // One instance per ordered axis list of length 1 (3) or 2 (6).
  static std::vector<DofQuaternionManifold> partial = [] {
    std::vector<DofQuaternionManifold> out;
    for (int a = 0; a < 3; ++a) out.emplace_back(std::vector<int>{a});
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        if (a != b) out.emplace_back(std::vector<int>{a, b});
      }
    }
    return out;
  }();
  if (axes.empty()) return nullptr;
  if (axes.size() >= 3) return &full;
  if (axes.size() == 1) return &partial[axes[0]];
  int index = 3;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      if (a == b) continue;
      if (a == axes[0] && b == axes[1]) return &partial[index];
      ++index;
    }
  }
  return &full;  // Unreachable for distinct axes in [0, 3).
}

}  // namespace mocapsolve
