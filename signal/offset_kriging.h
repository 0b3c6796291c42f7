// Gap refill by kriging the offset between a marker and its reference path (issue 16).
//
// With X a marker's path and R its reference (markers reconstructed from the robust
// kinematic solve X^), the offset d(t) = X(t) - R(t) is modelled, per marker and per axis,
// as a random process estimated from the take itself:
//   d(t) = mu + g(t) + n(t),
// mu a constant, g a stationary Ornstein-Uhlenbeck process (exponentially correlated:
// Cov[g(t), g(t + k)] = s_g^2 exp(-|k| / tau)), n white noise of variance s_n^2.
// Estimation (EstimateOffsetProcesses), per axis, from the frames where both paths are
// valid: mu is the median of d; the robust variogram
//   gamma(k) = 0.5 E[(d(t + k) - d(t))^2] = s_n^2 + s_g^2 (1 - exp(-k / tau)),  k >= 1,
// is taken at lags 1, 2, 3, 4, 6, 8, ... 256 frames as median((d(t + k) - d(t))^2) / (2 * 0.4549)
// (0.4549: the median of a chi-square with one degree of freedom, so a Gaussian gives the
// mean; undetected errors in d do not); the sill s_n^2 + s_g^2 is the robust variance of d,
// (1.4826 MAD)^2 (at lags far beyond the take's length the variogram alone cannot tell a
// long tau from a large s_g^2); and (s_n^2, tau) are fitted to the variogram by least
// squares in relative error: tau on a log grid of 2..4096 frames (a shorter correlation
// is white noise at the first lag), s_n^2 in [0, sill] for each tau.
// Fill (FillGapByKriging): the conditional mean of d inside the gap given up to K valid
// samples of d on each side (simple kriging with the known mean mu):
//   d^(t) = mu + c(t)^T C^-1 (d_o - mu),  C_ij = s_g^2 exp(-|t_i - t_j| / tau) + s_n^2 [i = j],
//   c_i(t) = s_g^2 exp(-|t - t_i| / tau),
// one K' x K' Cholesky solve per gap and axis (K' <= 2K), and X(t) = R(t) + d^(t).
// What it does: where d is noise-like (tau short against the gap, or s_n^2 large) the
// fill tends to R + mu and averages the noise of the edge samples instead of carrying the
// one edge sample's noise into the gap; where d is slow soft-tissue motion (tau long,
// s_n^2 small) it keeps the edge offsets and blends between them, like the edge blend of
// signal/gap_fill.h; a gap that runs to an end of the take decays from the one edge's
// offset toward mu with tau. Exact for a constant offset (s_g^2 = s_n^2 = 0 gives mu; any
// process gives mu + 0 when d_o = mu). The fill meets the data at the edges up to the
// noise the model attributes to the edge samples (continuous when s_n^2 = 0).
#ifndef MOCAPSOLVE_SIGNAL_OFFSET_KRIGING_H_
#define MOCAPSOLVE_SIGNAL_OFFSET_KRIGING_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"
#include "signal/gap_fill.h"

namespace mocapsolve {

// One marker's offset process, per axis (x, y, z); lengths in the markers' units, times
// in frames.
struct OffsetProcess {
  bool valid = false;  // False: too few samples to estimate (the caller fills otherwise).
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();              // mu.
  Eigen::Vector3d process_variance = Eigen::Vector3d::Zero();  // s_g^2.
  Eigen::Vector3d noise_variance = Eigen::Vector3d::Zero();    // s_n^2.
  Eigen::Vector3d time_constant = Eigen::Vector3d::Ones();     // tau, frames.
};

struct OffsetKrigingOptions {
  int samples_per_side = 10;  // K: valid samples of d conditioned on, on each side of a gap.
  int min_samples = 60;       // Fewer valid offsets than this: the marker's process is not valid.
};

// One process per marker of `observed` (same index), from the frames where both
// `observed` and `reference` are valid. Errors (one line) on mismatched sizes.
Status EstimateOffsetProcesses(const MarkerTrajectories& observed, const MarkerTrajectories& reference,
                               const OffsetKrigingOptions& options, std::vector<OffsetProcess>* processes);

// Fills `gap` of *markers with R + the conditional mean of d, conditioned on the samples
// valid in both `observed` and `reference` nearest the gap (up to K per side; `observed`
// is normally *markers before any fill, so one gap's fill is not data for the next).
// `reference` must be valid over the gap. A marker with no valid conditioning sample takes
// R + mu. Errors (one line) on mismatched sizes, a gap out of range, a reference sample
// missing in the gap, or an invalid process.
Status FillGapByKriging(const Gap& gap, const MarkerTrajectories& observed, const MarkerTrajectories& reference,
                        const OffsetProcess& process, const OffsetKrigingOptions& options,
                        MarkerTrajectories* markers);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_OFFSET_KRIGING_H_
