// The full 3 x 3 block update of solvers/block_sparse_cholesky.h, T <- T - A B^T, written
// out so that it runs in about two thirds of the time of the Eigen expression
//   T.noalias() -= A * B.transpose()
// with the same bits: each entry is T_ij - s_ij with s_ij = A_i0 B_j0 + A_i1 B_j1 + A_i2 B_j2
// summed as Eigen's fixed-size lazy product sums it (SSE2, no fused multiply-add): rows 0
// and 1, which it takes as one packet, as (A_i0 B_j0 + A_i1 B_j1) + A_i2 B_j2; row 2, the
// scalar tail, as A_20 B_j0 + (A_21 B_j1 + A_22 B_j2). block_update_3x3_test checks the bits
// against the Eigen expression, so a change of Eigen or of the compiler's flags shows there.
#ifndef MOCAPSOLVE_SOLVERS_BLOCK_UPDATE_3X3_H_
#define MOCAPSOLVE_SOLVERS_BLOCK_UPDATE_3X3_H_

#include <Eigen/Core>

namespace mocapsolve {

inline void SubtractProductTransposed3(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, Eigen::Matrix3d* target) {
  const double* x = a.data();  // Column-major: A_ik = x[i + 3k], B_jk = y[j + 3k].
  const double* y = b.data();
  double* t = target->data();
  for (int j = 0; j < 3; ++j) {
    const double b0 = y[j], b1 = y[j + 3], b2 = y[j + 6];
    t[3 * j] -= (x[0] * b0 + x[3] * b1) + x[6] * b2;
    t[3 * j + 1] -= (x[1] * b0 + x[4] * b1) + x[7] * b2;
    t[3 * j + 2] -= x[2] * b0 + (x[5] * b1 + x[8] * b2);
  }
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_BLOCK_UPDATE_3X3_H_
