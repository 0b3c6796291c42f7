// Cubic Cardinal spline interpolation at midpoints: the EXPAND step of the Laplacian
// pyramid (Huang, Boulic & Thalmann, section 2, steps 3-4: "get m-1 more samples ... at
// 1/2 t_i, 3/2 t_i, ... interpolated by cubic Cardinal splines").
//
// Samples p_0..p_{m-1} at unit spacing. The Cardinal spline is the cubic Hermite curve
// through the samples with tangents m_k = (1 - s) (p_{k+1} - p_{k-1}) / 2, s the tension
// (s = 0: Catmull-Rom, s = 1: zero tangents). Its value half-way between p_k and p_{k+1}:
//   p(k + 1/2) = (p_k + p_{k+1}) / 2 + (m_k - m_{k+1}) / 8.
// Ends: no wrap-around; the missing neighbours p_{-1} and p_m are extrapolated linearly
// (p_{-1} = 2 p_0 - p_1, p_m = 2 p_{m-1} - p_{m-2}), so the end tangents are one-sided
// differences and a straight line is reproduced exactly everywhere.
//
// ExpandMidpoints maps m coarse samples to n fine ones, n in {2m - 1, 2m}: fine sample
// 2k is coarse sample k, fine sample 2k+1 is p(k + 1/2); for n = 2m the last fine sample
// p(m - 1/2) lies half a coarse step past the end and is evaluated on the extrapolated
// segment [p_{m-1}, p_m]. Signals are #samples x #channels, row-major (one row per
// sample), so every channel is processed at once.
#ifndef MOCAPSOLVE_SIGNAL_CARDINAL_SPLINE_H_
#define MOCAPSOLVE_SIGNAL_CARDINAL_SPLINE_H_

#include <Eigen/Core>

namespace mocapsolve {

using Signal = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// fine (resized to fine_rows x coarse.cols()) = EXPAND(coarse). Requires coarse.rows() >= 2
// and fine_rows in {2 coarse.rows() - 1, 2 coarse.rows()} (CHECKed: programmer error).
void ExpandMidpoints(const Signal& coarse, int fine_rows, double tension, Signal* fine);

// Fused EXPAND and combination, one pass over memory (the pyramid's inner loop):
// out = alpha EXPAND(coarse) + beta other, with other.rows() fine rows. out must not
// alias coarse or other.
void ExpandAndCombine(const Signal& coarse, double tension, double alpha, const Signal& other,
                      double beta, Signal* out);
// The same on raw row-major buffers: coarse m x cols, other and out n x cols.
void ExpandAndCombine(const double* coarse, int m, int cols, double tension, double alpha,
                      const double* other, int n, double beta, double* out);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_CARDINAL_SPLINE_H_
