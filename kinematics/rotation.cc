#include "kinematics/rotation.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace mocapsolve {
namespace {

constexpr int kAxes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

}  // namespace

bool ParseEulerOrder(const std::string& text, EulerOrder* order) {
  if (text.size() != 3) return false;
  int axes[3];
  for (int i = 0; i < 3; ++i) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(text[i])));
    if (c < 'X' || c > 'Z') return false;
    axes[i] = c - 'X';
  }
  if (axes[0] == axes[1] || axes[1] == axes[2] || axes[0] == axes[2]) return false;
  *order = EulerOrderFromAxes(axes[0], axes[1], axes[2]);
  return true;
}

std::string EulerOrderName(EulerOrder order) {
  std::string name(3, ' ');
  for (int i = 0; i < 3; ++i) name[i] = static_cast<char>('X' + EulerAxis(order, i));
  return name;
}

int EulerAxis(EulerOrder order, int i) { return kAxes[static_cast<int>(order)][i]; }

EulerOrder EulerOrderFromAxes(int first, int second, int third) {
  for (int k = 0; k < 6; ++k) {
    if (kAxes[k][0] == first && kAxes[k][1] == second && kAxes[k][2] == third) {
      return static_cast<EulerOrder>(k);
    }
  }
  return EulerOrder::kXYZ;  // Unreachable for a permutation of {0, 1, 2}.
}

Eigen::Quaterniond QuaternionFromEuler(const Eigen::Vector3d& angles_rad, EulerOrder order) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (int i = 0; i < 3; ++i) {
    q = q * Eigen::Quaterniond(
                Eigen::AngleAxisd(angles_rad[i], Eigen::Vector3d::Unit(EulerAxis(order, i))));
  }
  return q;
}

Eigen::Vector3d EulerFromMatrix(const Eigen::Matrix3d& m, EulerOrder order) {
  // For R = R_i(a) R_j(b) R_k(c) with (i, j, k) a cyclic permutation (sign s = +1) or an
  // anticyclic one (s = -1): R(i,k) = s sin b, and the rest of row i is cos b times
  // (cos c, -s sin c) at columns (i, j).
  const int i = EulerAxis(order, 0), j = EulerAxis(order, 1), k = EulerAxis(order, 2);
  const double s = ((j - i + 3) % 3 == 1) ? 1.0 : -1.0;
  const double sin_b = std::clamp(s * m(i, k), -1.0, 1.0);
  const double cos_b = std::hypot(m(i, i), m(i, j));
  const double b = std::atan2(sin_b, cos_b);
  // c from row i (its entries carry cos b); at gimbal lock only a +- c is determined, so
  // c = 0. Then a comes from R R_k(-c) = R_i(a) R_j(b), whose column j is R_i(a) e_j:
  // well conditioned even when cos b is tiny, and consistent with the c chosen, so the
  // triple reproduces the rotation to round-off near the lock too.
  const double c = cos_b > 1e-12 ? std::atan2(-s * m(i, j), m(i, i)) : 0.0;
  const Eigen::Matrix3d m_without_c =
      m * Eigen::AngleAxisd(-c, Eigen::Vector3d::Unit(k)).toRotationMatrix();
  const double a = std::atan2(s * m_without_c(k, j), m_without_c(j, j));
  return Eigen::Vector3d(a, b, c);
}

Eigen::Vector3d EulerFromQuaternion(const Eigen::Quaterniond& q, EulerOrder order) {
  return EulerFromMatrix(q.normalized().toRotationMatrix(), order);
}

void AnglesAboutAxes(const Eigen::Quaterniond& q_in, const std::vector<int>& axes, double* angles,
                     Eigen::Matrix<double, Eigen::Dynamic, 3>* rate) {
  const Eigen::Quaterniond q = q_in.normalized();
  const int k = static_cast<int>(axes.size());
  if (k == 1) {
    const int a = axes[0];
    angles[0] = std::remainder(2.0 * std::atan2(q.coeffs()[a], q.w()), 2.0 * kPi);
    if (rate != nullptr) {
      // Only the a-th component of a local increment turns the angle (on the set).
      rate->setZero(1, 3);
      (*rate)(0, a) = 1.0;
    }
    return;
  }
  const int a = axes[0], b = axes[1], c = k == 3 ? axes[2] : 3 - axes[0] - axes[1];
  const Eigen::Vector3d t = EulerFromQuaternion(q, EulerOrderFromAxes(a, b, c));
  for (int i = 0; i < k; ++i) angles[i] = t[i];
  if (rate != nullptr) {
    const Eigen::Matrix3d rb = Eigen::AngleAxisd(t[1], Eigen::Vector3d::Unit(b)).toRotationMatrix();
    const Eigen::Matrix3d rc = Eigen::AngleAxisd(t[2], Eigen::Vector3d::Unit(c)).toRotationMatrix();
    Eigen::Matrix3d m;
    m.col(0) = (rb * rc).transpose() * Eigen::Vector3d::Unit(a);
    m.col(1) = rc.transpose() * Eigen::Vector3d::Unit(b);
    m.col(2) = Eigen::Vector3d::Unit(c);
    *rate = m.inverse().topRows(k);
  }
}

Eigen::Quaterniond ExpMap(const Eigen::Vector3d& v) {
  const double theta_sq = v.squaredNorm();
  double w, scale;  // q = (cos(theta/2), sin(theta/2)/theta * v)
  if (theta_sq < 1e-12) {
    // Taylor to the order where the next term is below double precision at theta < 1e-6.
    w = 1.0 - theta_sq / 8.0;
    scale = 0.5 - theta_sq / 48.0;
  } else {
    const double theta = std::sqrt(theta_sq);
    w = std::cos(0.5 * theta);
    scale = std::sin(0.5 * theta) / theta;
  }
  return Eigen::Quaterniond(w, scale * v.x(), scale * v.y(), scale * v.z());
}

Eigen::Vector3d LogMap(const Eigen::Quaterniond& q_in) {
  // Take the hemisphere w >= 0 so that the angle is in [0, pi].
  const Eigen::Quaterniond q = q_in.w() < 0.0 ? Eigen::Quaterniond(-q_in.coeffs()) : q_in;
  const Eigen::Vector3d xyz = q.vec();
  const double n = xyz.norm();
  double scale;  // v = scale * xyz, scale = theta / sin(theta/2), theta = 2 atan2(n, w)
  if (n < 1e-8) {
    // 2 atan2(n, w) / n = (2 / w) (1 - n^2 / (3 w^2) + ...); the next term is below
    // double precision here.
    scale = 2.0 / q.w() * (1.0 - n * n / (3.0 * q.w() * q.w()));
  } else {
    scale = 2.0 * std::atan2(n, q.w()) / n;
  }
  return scale * xyz;
}

void MakeSignContinuous(std::vector<Eigen::Quaterniond>* series) {
  for (size_t i = 1; i < series->size(); ++i) {
    if ((*series)[i].dot((*series)[i - 1]) < 0.0) {
      (*series)[i].coeffs() = -(*series)[i].coeffs();
    }
  }
}

double AngularDistance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return LogMap(a.conjugate() * b).norm();
}

}  // namespace mocapsolve
