// RightQuaternionManifold: the rotation parameter blocks of every problem.
//
// Ambient: a unit quaternion in Eigen's memory order (x, y, z, w), so that
// Eigen::Map<Eigen::Quaterniond> views it. Tangent: delta in R^3, the rotation vector of
// an increment in the joint's own (local) frame, as DESIGN.md fixes it:
//   Plus(q, delta)  = q * exp(delta)
//   Minus(y, x)     = log(x^-1 * y), on the 3-sphere (|Minus| may exceed pi, no
//                     hemisphere flip, so Plus(x, Minus(y, x)) = y exactly)
// (Ceres' EigenQuaternionManifold multiplies on the left instead.)
//
// PlusJacobian at delta = 0 is P(q) = 1/2 [q (x) (0, e_k)]_k, 4 x 3 row-major, with
// P^T P = I/4 for unit q. Residuals in this project compute their derivative in the
// tangent (J_tan, rows x 3, e.g. a_k x (p - o_j)) and report the ambient Jacobian
//   J_amb = J_tan * AmbientFromTangent(q),   AmbientFromTangent(q) = 4 P(q)^T (3 x 4),
// which satisfies J_amb * P = J_tan and vanishes along q itself; a residual that
// normalizes q before use has exactly this ambient derivative, so GradientChecker and
// autodiff twins agree with it.
#ifndef MOCAPSOLVE_SOLVERS_RIGHT_QUATERNION_MANIFOLD_H_
#define MOCAPSOLVE_SOLVERS_RIGHT_QUATERNION_MANIFOLD_H_

#include <vector>

#include <ceres/manifold.h>
#include <Eigen/Core>

namespace mocapsolve {

class RightQuaternionManifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 4; }
  int TangentSize() const override { return 3; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

// A joint that rotates about one or two of its local axes only (an ASF bone's dofs):
// the set { R_a0(t0) R_a1(t1) } of rotations with those Euler angles, in product order
// (Skeleton::rotation_axes). The chart is the angles themselves:
//   Plus(q, delta)  = Compose(Angles(q) + delta)
//   Minus(y, x)     = wrap(Angles(y) - Angles(x)) into (-pi, pi]
//   PlusJacobian    = [1/2 (0, e_a0) (x) q,  1/2 q (x) (0, e_a1)]   (4 x k, x y z w rows)
// Angles(q) projects q onto the set (exact for q on it: an Euler decomposition while the
// second angle is within pi/2, whose middle angle cannot go further; beyond it, the
// rank-1 factorization of q's components, which keeps Plus(q, 0) = +-q there instead of
// jumping to another point of the set: a solve that stepped past pi/2 then had every
// later step rejected and froze). For one axis this is q exp(d e_a);
// for two it is exact, unlike restricting increments q exp(d0 e_a0 + d1 e_a1), whose
// compositions would creep along the third axis. Residuals report the same ambient
// Jacobians as for the full manifold.
class DofQuaternionManifold : public ceres::Manifold {
 public:
  explicit DofQuaternionManifold(std::vector<int> axes);  // 1 or 2 distinct axes.
  int AmbientSize() const override { return 4; }
  int TangentSize() const override { return static_cast<int>(axes_.size()); }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;

  void Angles(const double* q, double* angles) const;
  void Compose(const double* angles, double* q) const;

  // PlusJacobian at a unit q already on the set (as every Plus leaves it), without the
  // Angles/Compose round trip (atan2, sin, cos) that projects it: the projection is q or -q
  // (its w is >= 0), so the same columns from q, negated when q's w < 0. False, with
  // `jacobian` untouched, if q is off the set by more than 1e-12 (one axis: the other vector
  // components; two: w v_c - eps v_a0 v_a1, which vanishes exactly on it), or if
  // |w| <= 1e-12. (That sign: for a stored q with w < 0, Plus(q, 0) = -q, and these columns
  // then pair with the ambient Jacobian at -q, not at q.)
  bool PlusJacobianOnSet(const double* x, double* jacobian) const;

 private:
  std::vector<int> axes_;
};

// The manifold of a joint's rotation block given its dof axes in product order
// (Skeleton::rotation_axes): RightQuaternionManifold for three, DofQuaternionManifold for
// one or two, nullptr for none (the block is then held constant). Shared instances; Manifold methods are
// const, so they are safe to share across threads (non-const only because Ceres' API
// takes Manifold*).
ceres::Manifold* RotationManifold(const std::vector<int>& axes);

// P(q): 4 x 3, d(q * exp(delta))/d delta at delta = 0, q in (x, y, z, w) order.
// Column k: 1/2 q (x) (0, e_k) = 1/2 (w e_k + v x e_k, -v_k). Inline: residuals call it
// in their inner loops.
inline Eigen::Matrix<double, 4, 3> QuaternionPlusJacobian(const double* q) {
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  Eigen::Matrix<double, 4, 3> p;
  p << 0.5 * w, -0.5 * z, 0.5 * y,
       0.5 * z, 0.5 * w, -0.5 * x,
       -0.5 * y, 0.5 * x, 0.5 * w,
       -0.5 * x, -0.5 * y, -0.5 * z;
  return p;
}
// 4 P(q)^T: 3 x 4, maps a tangent Jacobian to the ambient one (see above).
inline Eigen::Matrix<double, 3, 4> AmbientFromTangent(const double* q) {
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  Eigen::Matrix<double, 3, 4> a;
  a << 2.0 * w, 2.0 * z, -2.0 * y, -2.0 * x,
       -2.0 * z, 2.0 * w, 2.0 * x, -2.0 * y,
       2.0 * y, -2.0 * x, 2.0 * w, -2.0 * z;
  return a;
}

// The ambient Jacobian (3 x 4, row-major as Ceres wants it) of a residual that reads a
// quaternion block q_raw as q = q_raw / |q_raw|, from its tangent Jacobian d r / d delta
// (3 x 3): the 1 / |q_raw| is that normalization's (its radial part vanishes, since the
// rows of AmbientFromTangent(q) are orthogonal to q).
inline void AmbientJacobianOfNormalized(const Eigen::Matrix3d& tangent, const double* q_raw, double* jacobian) {
  Eigen::Vector4d q = Eigen::Map<const Eigen::Vector4d>(q_raw);
  const double norm = q.norm();
  q /= norm;
  Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> out(jacobian);
  out = tangent * AmbientFromTangent(q.data()) / norm;
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_RIGHT_QUATERNION_MANIFOLD_H_
