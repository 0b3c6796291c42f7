#include "signal/cardinal_spline.h"

#include <cassert>

namespace mocapsolve {

void ExpandMidpoints(const Signal& coarse, int fine_rows, double tension, Signal* fine) {
  const Signal none = Signal::Zero(fine_rows, coarse.cols());
  ExpandAndCombine(coarse, tension, 1.0, none, 0.0, fine);
}

void ExpandAndCombine(const Signal& coarse, double tension, double alpha, const Signal& other,
                      double beta, Signal* out) {
  assert(other.cols() == coarse.cols());
  assert(out != &other && out != &coarse);
  out->resize(other.rows(), other.cols());
  ExpandAndCombine(coarse.data(), static_cast<int>(coarse.rows()), static_cast<int>(coarse.cols()),
                   tension, alpha, other.data(), static_cast<int>(other.rows()), beta, out->data());
}

void ExpandAndCombine(const double* coarse, int m, int cols, double tension, double alpha,
                      const double* other, int n, double beta, double* out) {
  assert(m >= 2 && (n == 2 * m - 1 || n == 2 * m));
  // p(k + 1/2) = (1/2 + h)(p_k + p_{k+1}) - h (p_{k-1} + p_{k+2}), h = (1 - s) / 16.
  const double h = (1.0 - tension) / 16.0;
  const double ag = alpha * (0.5 + h), ah = alpha * h;
  const double* __restrict c = coarse;
  const double* __restrict o = other;
  double* __restrict d = out;
  const Eigen::Index stride = cols;
  // Row 2k (coarse sample k) and, for interior k, row 2k+1 (all four neighbours exist),
  // in one sweep.
  for (int k = 0; k < m; ++k) {
    const double* __restrict c1 = c + k * stride;
    const double* __restrict o0 = o + 2 * k * stride;
    double* __restrict d0 = d + 2 * k * stride;
    for (int i = 0; i < cols; ++i) d0[i] = alpha * c1[i] + beta * o0[i];
    if (k < 1 || k + 2 >= m) continue;
    const double* __restrict c0 = c1 - stride;
    const double* __restrict c2 = c1 + stride;
    const double* __restrict c3 = c2 + stride;
    const double* __restrict o1 = o0 + stride;
    double* __restrict d1 = d0 + stride;
    for (int i = 0; i < cols; ++i) {
      d1[i] = ag * (c1[i] + c2[i]) - ah * (c0[i] + c3[i]) + beta * o1[i];
    }
  }
  // Midpoints that need extrapolated neighbours: p_{-1}, p_m, p_{m+1} continue the end
  // segments linearly, p_{m-1+j} = p_{m-1} + j (p_{m-1} - p_{m-2}). Per channel i:
  auto sample = [&](int k, int i) -> double {
    if (k < 0) return c[i] + k * (c[stride + i] - c[i]);
    if (k >= m) {
      const double last = c[(m - 1) * stride + i];
      return last + (k - m + 1) * (last - c[(m - 2) * stride + i]);
    }
    return c[k * stride + i];
  };
  for (int k = 0; 2 * k + 1 < n; ++k) {
    if (k >= 1 && k + 2 < m) continue;  // Done above.
    const Eigen::Index row = (2 * k + 1) * stride;
    for (int i = 0; i < cols; ++i) {
      d[row + i] = ag * (sample(k, i) + sample(k + 1, i)) -
                   ah * (sample(k - 1, i) + sample(k + 2, i)) + beta * o[row + i];
    }
  }
}

}  // namespace mocapsolve
