// Gaussian and Laplacian pyramids of a multi-channel signal (Burt & Adelson 1983, as
// used for motion by Huang, Boulic & Thalmann, "Motion editing using multiresolution
// filtering"; equations numbered as in that paper).
//
//   G_0 = the signal, G_{l+1} = REDUCE(G_l)                       (eq. 1, generating_kernel.h)
//   L_l = G_l - EXPAND(G_{l+1}),  l = 0..N-1                      (eq. 3)
//   G_0 = G_N + sum_l L_l   (each term EXPANDed to full rate)     (eq. 4)
//   G'_0 = w_N G_N + sum_l w_l L_l                                (eq. 7, band editing)
// Collapsing runs from the top: G'_{N} = w_N G_N, G'_l = EXPAND(G'_{l+1}) + w_l L_l.
// EXPAND is cubic Cardinal spline interpolation (cardinal_spline.h; tension a parameter,
// 0 = Catmull-Rom). Building and collapsing use the same EXPAND, so with every weight 1
// the collapse returns the input up to rounding (the paper's small reconstruction error,
// from interpolating with a different operator than the one used to build, is gone).
//
// Any length n >= 1, not only 2^N + 1: level l+1 keeps the samples at the even positions
// of level l, n_{l+1} = ceil(n_l / 2) = (n_l + 1) / 2, so sample i of level l sits at
// time 2^l i (in frames of G_0; eq. 5). For even n_l the last sample of level l has no
// coarse sample under it and EXPAND extrapolates it (cardinal_spline.h). A level is
// reduced only if it has >= 3 samples, so MaxPyramidLevels(n) levels at most.
//
// Ends, no wrap-around: REDUCE needs G_l(-2), G_l(-1) and the two past the end; they are
// extended by point reflection about the end sample, G_l(-k) = 2 G_l(0) - G_l(k)
// (likewise at the far end). This keeps a straight line straight (no end flattening of a
// drifting root) and, as a + 2b + 2c = 1, copies the first sample (and, for odd n_l, the
// last) to the next level exactly, which is what the paper does.
//
// Signals are #samples x #channels, row-major (Signal, cardinal_spline.h); every channel
// is filtered independently with the same kernel.
#ifndef MOCAPSOLVE_SIGNAL_LAPLACIAN_PYRAMID_H_
#define MOCAPSOLVE_SIGNAL_LAPLACIAN_PYRAMID_H_

#include <string>
#include <vector>

#include "kinematics/status.h"
#include "signal/cardinal_spline.h"
#include "signal/generating_kernel.h"

namespace mocapsolve {

struct PyramidOptions {
  GeneratingKernel kernel;  // a = 0.4 by default.
  double tension = 0.0;     // Cardinal spline tension of EXPAND, in [0, 1]; 0 = Catmull-Rom.
  int levels = 0;           // N, the number of REDUCE steps; 0 = MaxPyramidLevels(n).

  Status Validate() const;
};

// Largest N for which every reduced level has >= 2 samples (0 for n < 3).
int MaxPyramidLevels(int num_samples);
// Samples of level `level` for a signal of num_samples (level 0: num_samples).
int PyramidLevelSize(int num_samples, int level);

struct LaplacianPyramid {
  PyramidOptions options;          // levels resolved (never 0 unless the signal is short).
  std::vector<Signal> gaussian;    // G_1..G_N: gaussian[l - 1] is G_l (G_0 is the input).
  std::vector<Signal> laplacian;   // L_0..L_{N-1}: laplacian[l] is L_l, n_l rows.

  int levels() const { return static_cast<int>(laplacian.size()); }
  const Signal& top() const { return gaussian.back(); }  // G_N; levels() >= 1.
};

// G_{l+1} = REDUCE(G_l) (eq. 1 with point-reflected ends). fine.rows() >= 3.
void Reduce(const Signal& fine, const GeneratingKernel& kernel, Signal* coarse);

// Builds both pyramids. Fails (naming the option) if the options are invalid,
// options.levels exceeds MaxPyramidLevels(signal.rows()) or a sample is not finite. Reuses *pyramid's storage
// when the sizes match (no allocation on a rebuild of a same-sized signal).
Status BuildLaplacianPyramid(const Signal& signal, const PyramidOptions& options,
                             LaplacianPyramid* pyramid);

// Eq. 7: w_N G_N + sum w_l L_l collapsed to full rate. weights: N + 1 values
// w_0 (finest band) .. w_{N-1}, w_N (the top Gaussian), or empty for all ones (eq. 4).
// scratch (optional) is reused between calls. The weight count is asserted (callers
// validate user input with CheckBandWeights). A pyramid of 0 levels gives an empty *out.
void ReconstructSignal(const LaplacianPyramid& pyramid, const std::vector<double>& weights,
                       Signal* out, Signal* scratch = nullptr);

// Error naming the band (laplacian[l], top) unless the pyramid has BuildLaplacianPyramid's shape: N >= 1
// bands, N <= MaxPyramidLevels(n) for n = laplacian[0].rows(), laplacian[l] of
// PyramidLevelSize(n, l) rows, the top (gaussian.back()) of PyramidLevelSize(n, N), every
// band and the top as many columns (>= 1) as laplacian[0], and finite samples. ReconstructSignal assumes it
// (a pyramid assembled from user arrays must pass this first).
Status CheckPyramidShape(const LaplacianPyramid& pyramid);

// Weights of a pyramid with `levels` bands that drop the `dropped` finest bands
// (w_0..w_{dropped-1} = 0, the rest 1): data filtering (paper section 5).
std::vector<double> DropFinestBands(int levels, int dropped);

// Status naming `what` (a flag or field) if weights is not N + 1 finite values.
Status CheckBandWeights(const std::vector<double>& weights, int levels, const std::string& what);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_LAPLACIAN_PYRAMID_H_
