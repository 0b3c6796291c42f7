#include "signal/offset_kriging.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Cholesky>

#include "signal/select_non_negative.h"

namespace mocapsolve {
namespace {

// Lags (frames) of the variogram: dense where noise and short correlations show, sparse
// where slow soft tissue does.
constexpr int kLags[] = {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256};
constexpr int kMinPairs = 20;  // A lag with fewer pairs of valid offsets is not used.
// Median of a chi-square variable with one degree of freedom: median(z^2) for z ~ N(0, 1).
constexpr double kChiSquare1Median = 0.454936;

bool Usable(const MarkerTrajectories& x, const MarkerTrajectories& r, int f, int m) {
  return x.valid(f, m) && r.valid(f, m);
}

// Fits gamma(k) = V - (V - s_n^2) exp(-k / tau) (the sill V = s_n^2 + s_g^2 given) to the
// variogram (lags, values > 0) by least squares in relative error, 0 <= s_n^2 <= V, tau on
// a log grid.
void FitVariogram(const std::vector<double>& lags, const std::vector<double>& gamma, double sill,
                  double* noise_variance, double* time_constant) {
  double best = std::numeric_limits<double>::infinity();
  *noise_variance = sill;
  *time_constant = 2.0;
  const int n = static_cast<int>(lags.size());
  std::vector<double> e(n);
  // From 2 frames: below, the exponential has decayed by the first lag and is noise.
  for (double tau = 2.0; tau <= 4096.0; tau *= std::pow(2.0, 0.125)) {
    // min over a of sum_k ((a e_k - (gamma_k - V (1 - e_k))) / gamma_k)^2.
    double see = 0.0, sey = 0.0;
    for (int k = 0; k < n; ++k) {
      e[k] = std::exp(-lags[k] / tau);
      const double w = 1.0 / (gamma[k] * gamma[k]);
      see += w * e[k] * e[k];
      sey += w * e[k] * (gamma[k] - sill * (1.0 - e[k]));
    }
    const double a = see > 0.0 ? std::clamp(sey / see, 0.0, sill) : sill;
    double cost = 0.0;
    for (int k = 0; k < n; ++k) {
      const double r = (sill - (sill - a) * e[k] - gamma[k]) / gamma[k];
      cost += r * r;
    }
    if (cost < best) best = cost, *noise_variance = a, *time_constant = tau;
  }
}

}  // namespace

Status EstimateOffsetProcesses(const MarkerTrajectories& observed, const MarkerTrajectories& reference,
                               const OffsetKrigingOptions& options, std::vector<OffsetProcess>* processes) {
  const int frames = observed.num_frames();
  if (reference.num_frames() != frames || reference.num_markers() != observed.num_markers()) {
    return Status::Error("offset process: reference has " + std::to_string(reference.num_frames()) + " frames x " +
                         std::to_string(reference.num_markers()) + " markers, markers " + std::to_string(frames) +
                         " x " + std::to_string(observed.num_markers()));
  }
  processes->assign(observed.num_markers(), OffsetProcess());
  std::vector<double> values, squares, scratch;  // scratch: SelectNonNegative's.
  std::vector<char> usable(frames);
  std::vector<Eigen::Vector3d> d(frames);
  for (int m = 0; m < observed.num_markers(); ++m) {
    int count = 0;
    for (int f = 0; f < frames; ++f) {
      usable[f] = Usable(observed, reference, f, m);
      if (usable[f]) d[f] = observed.position(f, m) - reference.position(f, m), ++count;
    }
    if (count < std::max(2, options.min_samples)) continue;
    OffsetProcess& p = (*processes)[m];
    p.valid = true;
    for (int axis = 0; axis < 3; ++axis) {
      values.clear();
      for (int f = 0; f < frames; ++f) {
        if (usable[f]) values.push_back(d[f][axis]);
      }
      std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
      p.mean[axis] = values[values.size() / 2];
      // The sill: the robust variance of d about its median, (1.4826 MAD)^2.
      for (double& v : values) v = std::abs(v - p.mean[axis]);
      const double mad = SelectNonNegative(&values, values.size() / 2, &scratch);
      const double sill = std::pow(1.4826 * mad, 2);
      std::vector<double> lags, gamma;
      for (const int lag : kLags) {
        squares.clear();
        for (int f = 0; f + lag < frames; ++f) {
          if (usable[f] && usable[f + lag]) {
            const double diff = d[f + lag][axis] - d[f][axis];
            squares.push_back(diff * diff);
          }
        }
        if (static_cast<int>(squares.size()) < kMinPairs) continue;
        const double g = SelectNonNegative(&squares, squares.size() / 2, &scratch) / (2.0 * kChiSquare1Median);
        if (g > 0.0 && std::isfinite(g)) lags.push_back(lag), gamma.push_back(g);
      }
      // No variation at any lag (a constant offset): d = mu.
      if (lags.empty() || !(sill > 0.0)) continue;
      FitVariogram(lags, gamma, sill, &p.noise_variance[axis], &p.time_constant[axis]);
      p.process_variance[axis] = sill - p.noise_variance[axis];
    }
  }
  return Status::Ok();
}

Status FillGapByKriging(const Gap& gap, const MarkerTrajectories& observed, const MarkerTrajectories& reference,
                        const OffsetProcess& process, const OffsetKrigingOptions& options,
                        MarkerTrajectories* markers) {
  const int n = markers->num_frames();
  if (reference.num_frames() != n || reference.num_markers() != markers->num_markers() ||
      observed.num_frames() != n || observed.num_markers() != markers->num_markers()) {
    return Status::Error("kriging fill: reference has " + std::to_string(reference.num_frames()) + " frames x " +
                         std::to_string(reference.num_markers()) + " markers, observed " +
                         std::to_string(observed.num_frames()) + " x " + std::to_string(observed.num_markers()) +
                         ", markers " + std::to_string(n) + " x " + std::to_string(markers->num_markers()));
  }
  if (gap.first < 0 || gap.last >= n || gap.first > gap.last || gap.marker < 0 ||
      gap.marker >= markers->num_markers()) {
    return Status::Error("kriging fill: gap out of range");
  }
  if (!process.valid) return Status::Error("kriging fill: no offset process for marker '" + reference.label(gap.marker) + "'");
  const int m = gap.marker;
  for (int f = gap.first; f <= gap.last; ++f) {
    if (!reference.valid(f, m)) {
      return Status::Error("kriging fill: reference marker '" + reference.label(m) + "' is missing at frame " +
                           std::to_string(f));
    }
  }
  // The conditioning samples: up to K usable frames on each side, nearest first.
  std::vector<int> times;
  const int k_side = std::max(1, options.samples_per_side);
  for (int f = gap.first - 1, found = 0; f >= 0 && found < k_side; --f) {
    if (Usable(observed, reference, f, m)) times.push_back(f), ++found;
  }
  for (int f = gap.last + 1, found = 0; f < n && found < k_side; ++f) {
    if (Usable(observed, reference, f, m)) times.push_back(f), ++found;
  }
  const int k = static_cast<int>(times.size());
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(k, 3);  // C^-1 (d_o - mu), per axis.
  for (int axis = 0; axis < 3 && k > 0; ++axis) {
    const double sg = process.process_variance[axis], sn = process.noise_variance[axis];
    const double tau = process.time_constant[axis];
    if (!(sg > 0.0)) continue;
    Eigen::MatrixXd c(k, k);
    Eigen::VectorXd y(k);
    for (int i = 0; i < k; ++i) {
      y[i] = observed.position(times[i], m)[axis] - reference.position(times[i], m)[axis] - process.mean[axis];
      for (int j = 0; j < k; ++j) c(i, j) = sg * std::exp(-std::abs(times[i] - times[j]) / tau);
      // The noise, and a floor that keeps C positive definite when tau is long against the
      // samples' spread (the columns then nearly coincide).
      c(i, i) += sn + 1e-9 * sg;
    }
    weights.col(axis) = c.llt().solve(y);
  }
  for (int f = gap.first; f <= gap.last; ++f) {
    Eigen::Vector3d offset = process.mean;
    for (int axis = 0; axis < 3; ++axis) {
      const double sg = process.process_variance[axis], tau = process.time_constant[axis];
      if (!(sg > 0.0)) continue;
      for (int i = 0; i < k; ++i) offset[axis] += sg * std::exp(-std::abs(f - times[i]) / tau) * weights(i, axis);
    }
    markers->SetSample(f, m, reference.position(f, m) + offset);
  }
  return Status::Ok();
}

}  // namespace mocapsolve
