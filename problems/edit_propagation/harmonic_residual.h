// HarmonicEdgeResidual: one edge of the pose graph in the harmonic-function energy of Zhu,
// Ghahramani & Lafferty (2003), "Semi-supervised learning using Gaussian fields and
// harmonic functions":
//
//   E(u) = 1/2 sum_{edges (i, j)} K_ij (u_i - u_j)^2,      r_ij = sqrt(K_ij) (u_i - u_j)
//
// one scalar u per frame (the falloff weight of an edit; dimensionless), K_ij >= 0 the
// pose kernel on the edge (dimensionless). Minimizing E with the labelled frames' u held
// fixed gives the harmonic field: at every free frame u_i is the K-weighted mean of its
// neighbours' u (the graph Laplacian L = D - K vanishes on the free rows).
//
// Parameter blocks, in order: u_i (1 double), u_j (1 double). Residual: 1 row.
// Jacobians (1 x 1 each; either may be null, and `jacobians` itself may be null):
//   d r / d u_i = sqrt(K_ij),   d r / d u_j = -sqrt(K_ij).
//
// HarmonicEdgeFunctor is the templated twin (ceres::AutoDiffCostFunction<_, 1, 1, 1>)
// used by the tests.
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_HARMONIC_RESIDUAL_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_HARMONIC_RESIDUAL_H_

#include <cmath>

#include <ceres/sized_cost_function.h>

namespace mocapsolve {

class HarmonicEdgeResidual : public ceres::SizedCostFunction<1, 1, 1> {
 public:
  // kernel = K_ij >= 0 (CHECKed).
  explicit HarmonicEdgeResidual(double kernel);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  double sqrt_kernel() const { return sqrt_kernel_; }

 private:
  double sqrt_kernel_;
};

struct HarmonicEdgeFunctor {
  explicit HarmonicEdgeFunctor(double kernel) : sqrt_kernel(std::sqrt(kernel)) {}
  template <typename T>
  bool operator()(const T* u_i, const T* u_j, T* residual) const {
    residual[0] = sqrt_kernel * (u_i[0] - u_j[0]);
    return true;
  }
  double sqrt_kernel;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_HARMONIC_RESIDUAL_H_
