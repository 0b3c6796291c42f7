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

// P(q): 4 x 3, d(q * exp(delta))/d delta at delta = 0, q in (x, y, z, w) order.
Eigen::Matrix<double, 4, 3> QuaternionPlusJacobian(const double* q);
// 4 P(q)^T: 3 x 4, maps a tangent Jacobian to the ambient one (see above).
Eigen::Matrix<double, 3, 4> AmbientFromTangent(const double* q);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_RIGHT_QUATERNION_MANIFOLD_H_
