#include "signal/laplacian_pyramid.h"

#include <cassert>
#include <cmath>
#include <string>
#include <utility>

namespace mocapsolve {

Status PyramidOptions::Validate() const {
  Status status = kernel.Validate();
  if (!status.ok()) return status;
  if (!(tension >= 0.0 && tension <= 1.0)) return Status::Error("tension must be in [0, 1]");
  if (levels < 0) return Status::Error("levels must be >= 0");
  return Status::Ok();
}

int MaxPyramidLevels(int num_samples) {
  int levels = 0;
  for (int n = num_samples; n >= 3; n = (n + 1) / 2) ++levels;
  return levels;
}

int PyramidLevelSize(int num_samples, int level) {
  int n = num_samples;
  for (int l = 0; l < level; ++l) n = (n + 1) / 2;
  return n;
}

void Reduce(const Signal& fine, const GeneratingKernel& kernel, Signal* coarse) {
  const int n = static_cast<int>(fine.rows());
  const int cols = static_cast<int>(fine.cols());
  assert(n >= 3);
  const int m = (n + 1) / 2;
  coarse->resize(m, cols);
  const double a = kernel.a, b = kernel.b(), c = kernel.c();
  // Interior: 2i - 2 >= 0 and 2i + 2 <= n - 1.
  for (int i = 1; 2 * i + 2 < n; ++i) {
    const double* __restrict f0 = fine.data() + static_cast<Eigen::Index>(2 * i - 2) * cols;
    const double* __restrict f1 = f0 + cols;
    const double* __restrict f2 = f1 + cols;
    const double* __restrict f3 = f2 + cols;
    const double* __restrict f4 = f3 + cols;
    double* __restrict d = coarse->data() + static_cast<Eigen::Index>(i) * cols;
    for (int k = 0; k < cols; ++k) d[k] = a * f2[k] + b * (f1[k] + f3[k]) + c * (f0[k] + f4[k]);
  }
  // Ends: samples outside [0, n) by point reflection about the end sample.
  using Row = Eigen::RowVectorXd;
  auto sample = [&](int k) -> Row {
    if (k < 0) return 2.0 * fine.row(0) - fine.row(-k);
    if (k >= n) return 2.0 * fine.row(n - 1) - fine.row(2 * (n - 1) - k);
    return fine.row(k);
  };
  for (int i = 0; i < m; ++i) {
    if (i >= 1 && 2 * i + 2 < n) continue;
    coarse->row(i) = a * sample(2 * i) + b * (sample(2 * i - 1) + sample(2 * i + 1)) +
                     c * (sample(2 * i - 2) + sample(2 * i + 2));
  }
}

Status BuildLaplacianPyramid(const Signal& signal, const PyramidOptions& options,
                             LaplacianPyramid* pyramid) {
  Status status = options.Validate();
  if (!status.ok()) return status;
  const int n = static_cast<int>(signal.rows());
  const int max_levels = MaxPyramidLevels(n);
  if (options.levels > max_levels) {
    return Status::Error("levels " + std::to_string(options.levels) + " too many for " +
                         std::to_string(n) + " samples (at most " + std::to_string(max_levels) +
                         ")");
  }
  if (!signal.allFinite()) return Status::Error("signal has non-finite samples");
  const int levels = options.levels == 0 ? max_levels : options.levels;
  pyramid->options = options;
  pyramid->options.levels = levels;
  pyramid->gaussian.resize(levels);
  pyramid->laplacian.resize(levels);
  for (int l = 0; l < levels; ++l) {
    const Signal& finer = l == 0 ? signal : pyramid->gaussian[l - 1];
    Reduce(finer, options.kernel, &pyramid->gaussian[l]);
    // Eq. 3: L_l = G_l - EXPAND(G_{l+1}), fused.
    ExpandAndCombine(pyramid->gaussian[l], options.tension, -1.0, finer, 1.0,
                     &pyramid->laplacian[l]);
  }
  return Status::Ok();
}

void ReconstructSignal(const LaplacianPyramid& pyramid, const std::vector<double>& weights,
                       Signal* out, Signal* scratch) {
  const int levels = pyramid.levels();
  assert(weights.empty() || static_cast<int>(weights.size()) == levels + 1);
  auto weight = [&](int l) { return weights.empty() ? 1.0 : weights[l]; };
  if (levels == 0) {
    out->resize(0, 0);
    return;
  }
  const int cols = static_cast<int>(pyramid.top().cols());
  // G'_l lives in *out for even l and in *scratch for odd l: both are sized once (no
  // reallocation when called again on a pyramid of the same size).
  Signal local;
  Signal* other = scratch != nullptr ? scratch : &local;
  out->resize(pyramid.laplacian[0].rows(), cols);
  other->resize(pyramid.laplacian[levels > 1 ? 1 : 0].rows(), cols);
  auto buffer = [&](int l) { return l % 2 == 0 ? out->data() : other->data(); };
  const Signal& top = pyramid.top();
  Eigen::Map<Signal>(buffer(levels), top.rows(), cols) = weight(levels) * top;
  int rows = static_cast<int>(top.rows());
  for (int l = levels - 1; l >= 0; --l) {
    const Signal& band = pyramid.laplacian[l];
    ExpandAndCombine(buffer(l + 1), rows, cols, pyramid.options.tension, 1.0, band.data(),
                     static_cast<int>(band.rows()), weight(l), buffer(l));
    rows = static_cast<int>(band.rows());
  }
}

Status CheckPyramidShape(const LaplacianPyramid& pyramid) {
  const int levels = pyramid.levels();
  if (levels < 1) return Status::Error("laplacian: expected at least one band");
  if (pyramid.gaussian.empty()) return Status::Error("top: missing");
  const Eigen::Index n = pyramid.laplacian[0].rows(), cols = pyramid.laplacian[0].cols();
  const int max_levels = n > (1 << 30) ? 31 : MaxPyramidLevels(static_cast<int>(n));
  if (levels > max_levels) {
    return Status::Error("laplacian: " + std::to_string(levels) + " bands are too many for " + std::to_string(n) +
                         " samples in laplacian[0] (at most " + std::to_string(max_levels) + ")");
  }
  if (cols < 1) return Status::Error("laplacian[0]: no channels");
  auto check = [&](const Signal& s, int level, const std::string& name) {
    const int rows = PyramidLevelSize(static_cast<int>(n), level);
    if (s.rows() != rows || s.cols() != cols) {
      return Status::Error(name + ": shape (" + std::to_string(s.rows()) + ", " + std::to_string(s.cols()) +
                           "), expected (" + std::to_string(rows) + ", " + std::to_string(cols) +
                           ") for a pyramid of " + std::to_string(n) + " samples");
    }
    if (!s.allFinite()) return Status::Error(name + ": non-finite samples");
    return Status::Ok();
  };
  for (int l = 0; l < levels; ++l) {
    Status status = check(pyramid.laplacian[l], l, "laplacian[" + std::to_string(l) + "]");
    if (!status.ok()) return status;
  }
  return check(pyramid.top(), levels, "top");
}

std::vector<double> DropFinestBands(int levels, int dropped) {
  std::vector<double> weights(levels + 1, 1.0);
  for (int l = 0; l < dropped && l < levels; ++l) weights[l] = 0.0;
  return weights;
}

Status CheckBandWeights(const std::vector<double>& weights, int levels, const std::string& what) {
  if (static_cast<int>(weights.size()) != levels + 1) {
    return Status::Error(what + ": expected " + std::to_string(levels + 1) +
                         " weights (w_0 finest band .. w_N top), got " +
                         std::to_string(weights.size()));
  }
  for (double w : weights) {
    if (!std::isfinite(w)) return Status::Error(what + ": weights must be finite");
  }
  return Status::Ok();
}

}  // namespace mocapsolve
