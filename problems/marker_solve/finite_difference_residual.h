// FiniteDifferenceResidual: smoothness of a parameter over consecutive frames, the
// clip solve's temporal term.
//
//   r = scale * weight * sum_i c_i s_i x_i                  (size rows)
//
// over N parameter blocks x_0..x_{N-1} of equal size (consecutive frames of one joint's
// rotation, or of the root translation), with coefficients c = (-1, 1) (velocity) or
// (1, -2, 1) (acceleration). For quaternion blocks (4, Eigen order, on
// RightQuaternionManifold) signs s_i = sign(x_i . x_{N-1}) align every quaternion with the
// last one (q and -q are one rotation) and scale = 2, so that |r| ~ weight * (angle in
// radians) for small differences (chordal distance); for translations s_i = 1, scale = 1
// (weight per length unit).
//
// Jacobians: d r / d x_i = scale * weight * c_i s_i I (size x size), exact away from the
// measure-zero set where a sign flips.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_FINITE_DIFFERENCE_RESIDUAL_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_FINITE_DIFFERENCE_RESIDUAL_H_

#include <vector>

#include <ceres/cost_function.h>

namespace mocapsolve {

enum class SmoothnessOrder { kVelocity = 1, kAcceleration = 2 };

class FiniteDifferenceResidual : public ceres::CostFunction {
 public:
  // quaternion: blocks are 4-vectors (x, y, z, w); otherwise 3-vectors.
  FiniteDifferenceResidual(SmoothnessOrder order, bool quaternion, double weight);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  std::vector<double> coefficients_;
  bool quaternion_;
  int size_;
  double scaled_weight_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_FINITE_DIFFERENCE_RESIDUAL_H_
