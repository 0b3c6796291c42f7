#include "problems/edit_propagation/falloff_analysis.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mocapsolve {

int DetectPosePeriod(const Eigen::MatrixXd& features, int min_lag) {
  const int n = static_cast<int>(features.rows());
  const int max_lag = 2 * n / 3;
  if (max_lag < 2) return 0;
  std::vector<double> s(max_lag + 1, 0.0);
  for (int l = 1; l <= max_lag; ++l) {
    double sum = 0.0;
    for (int i = 0; i + l < n; ++i) sum += (features.row(i + l) - features.row(i)).norm();
    s[l] = sum / (n - l);
  }
  constexpr int kWindow = 3;
  double highest = 0.0;
  for (int l = 1; l <= max_lag; ++l) {
    highest = std::max(highest, s[l]);
    if (l < std::max(min_lag, kWindow + 1) || l + kWindow > max_lag) continue;
    bool local_min = true;
    for (int d = -kWindow; d <= kWindow && local_min; ++d) local_min = s[l] <= s[l + d];
    if (local_min && s[l] < 0.5 * highest) return l;
  }
  return 0;
}

PhaseFrames FindPhaseFrames(const Eigen::MatrixXd& features, int frame, int period) {
  PhaseFrames result;
  const int n = static_cast<int>(features.rows());
  if (period <= 0) return result;
  const int reach = std::max(1, period / 4);
  auto search = [&](double centre, bool nearest) {
    const int c = static_cast<int>(std::lround(centre));
    int best = -1;
    double best_d = nearest ? std::numeric_limits<double>::infinity() : -1.0;
    for (int j = std::max(0, c - reach); j <= std::min(n - 1, c + reach); ++j) {
      const double d = (features.row(j) - features.row(frame)).norm();
      if (nearest ? d < best_d : d > best_d) best = j, best_d = d;
    }
    return best;
  };
  for (int k = -(n / period + 1); k <= n / period + 1; ++k) {
    const double same = frame + static_cast<double>(k) * period;
    if (k != 0 && same >= 0 && same < n) {
      const int j = search(same, true);
      if (j >= 0 && std::abs(j - frame) > reach) result.same.push_back(j);
    }
  }
  // Opposite phase: halfway between consecutive same-phase frames (the edit included),
  // and half a period beyond the first and the last.
  std::vector<int> all = result.same;
  all.push_back(frame);
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  if (all.front() - period / 2 >= 0) result.opposite.push_back(all.front() - period / 2);
  for (size_t k = 0; k + 1 < all.size(); ++k) result.opposite.push_back((all[k] + all[k + 1]) / 2);
  if (all.back() + period / 2 < n) result.opposite.push_back(all.back() + period / 2);
  return result;
}

double SecondDifference(const Eigen::VectorXd& values, int frame) {
  if (frame <= 0 || frame + 1 >= values.size()) return std::numeric_limits<double>::quiet_NaN();
  return values[frame - 1] - 2.0 * values[frame] + values[frame + 1];
}

double KinkRatio(const Eigen::VectorXd& values, int frame) {
  if (frame < 2 || frame + 2 >= values.size()) return std::numeric_limits<double>::quiet_NaN();
  const double slopes = 0.5 * (std::abs(values[frame + 2] - values[frame + 1]) +
                               std::abs(values[frame - 1] - values[frame - 2]));
  if (!(slopes > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return std::abs(SecondDifference(values, frame)) / slopes;
}

int FalloffEnd(const Eigen::VectorXd& weight, int frame, int direction, double threshold) {
  for (int j = frame + direction; j >= 0 && j < weight.size(); j += direction) {
    if (weight[j] < threshold) return j;
  }
  return -1;
}

}  // namespace mocapsolve
