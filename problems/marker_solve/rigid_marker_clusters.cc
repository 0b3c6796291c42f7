#include "problems/marker_solve/rigid_marker_clusters.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mocapsolve {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The q-quantile of `v` (reordered), 0 <= q <= 1.
double Quantile(std::vector<double>* v, double q) {
  const size_t k = std::min(v->size() - 1, static_cast<size_t>(q * static_cast<double>(v->size() - 1) + 0.5));
  std::nth_element(v->begin(), v->begin() + k, v->end());
  return (*v)[k];
}

}  // namespace

PairwiseSpread ComputePairwiseSpread(const MarkerTrajectories& take, const std::vector<int>& markers,
                                     double metres_per_unit, const RigidClusterOptions& options) {
  const int n = static_cast<int>(markers.size());
  PairwiseSpread pairs;
  pairs.spread = Eigen::MatrixXd::Constant(n, n, kInf);
  pairs.distance = Eigen::MatrixXd::Constant(n, n, std::numeric_limits<double>::quiet_NaN());
  const int frames = take.num_frames();
  const int step = std::max(1, frames / std::max(1, options.max_frames));
  std::vector<int> sampled;
  for (int f = 0; f < frames; f += step) sampled.push_back(f);
  std::vector<double> d;
  d.reserve(sampled.size());
  for (int a = 0; a < n; ++a) {
    pairs.spread(a, a) = 0.0;
    pairs.distance(a, a) = 0.0;
    for (int b = a + 1; b < n; ++b) {
      d.clear();
      for (int f : sampled) {
        if (!take.valid(f, markers[a]) || !take.valid(f, markers[b])) continue;
        d.push_back((take.position(f, markers[a]) - take.position(f, markers[b])).norm() * metres_per_unit);
      }
      if (static_cast<int>(d.size()) < options.min_covisible_frames) continue;
      const double q10 = Quantile(&d, 0.1), q90 = Quantile(&d, 0.9), median = Quantile(&d, 0.5);
      pairs.spread(a, b) = pairs.spread(b, a) = (q90 - q10) / 2.563;
      pairs.distance(a, b) = pairs.distance(b, a) = median;
    }
  }
  return pairs;
}

double MeanClusterSpread(const PairwiseSpread& pairs, const std::vector<int>& a, const std::vector<int>& b) {
  double sum = 0.0;
  int finite = 0, total = 0;
  for (int i : a) {
    for (int j : b) {
      ++total;
      if (std::isfinite(pairs.spread(i, j))) sum += pairs.spread(i, j), ++finite;
    }
  }
  // Dropouts leave some pairs without evidence; most must have it.
  if (finite == 0 || 2 * finite < total) return kInf;
  return sum / finite;
}

double MinClusterSpread(const PairwiseSpread& pairs, const std::vector<int>& a, const std::vector<int>& b) {
  double best = kInf;
  for (int i : a) {
    for (int j : b) best = std::min(best, pairs.spread(i, j));
  }
  return best;
}

std::vector<std::vector<int>> ClusterRigidMarkers(const PairwiseSpread& pairs, const RigidClusterOptions& options) {
  const int n = static_cast<int>(pairs.spread.rows());
  std::vector<std::vector<int>> clusters(n);
  for (int i = 0; i < n; ++i) clusters[i] = {i};
  auto too_wide = [&](const std::vector<int>& a, const std::vector<int>& b) {
    for (int i : a) {
      for (int j : b) {
        if (pairs.distance(i, j) > options.max_extent) return true;
      }
    }
    return false;
  };
  while (clusters.size() > 1) {
    double best = kInf;
    int best_a = -1, best_b = -1;
    for (size_t a = 0; a < clusters.size(); ++a) {
      for (size_t b = a + 1; b < clusters.size(); ++b) {
        const double s = MeanClusterSpread(pairs, clusters[a], clusters[b]);
        if (s < best && !too_wide(clusters[a], clusters[b])) best = s, best_a = static_cast<int>(a), best_b = static_cast<int>(b);
      }
    }
    if (best_a < 0 || !(best <= options.max_spread)) break;
    clusters[best_a].insert(clusters[best_a].end(), clusters[best_b].begin(), clusters[best_b].end());
    clusters.erase(clusters.begin() + best_b);
  }
  std::stable_sort(clusters.begin(), clusters.end(),
                   [](const std::vector<int>& a, const std::vector<int>& b) { return a.size() > b.size(); });
  return clusters;
}

}  // namespace mocapsolve
