#include "problems/marker_label/gated_assignment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "problems/marker_repair/unlabelled_assignment.h"

namespace mocapsolve {
namespace {

constexpr double kForbidden = 1e6;  // Cost of a pair that is not a candidate.
constexpr size_t kMarginRows = 6;  // Larger groups (wide gates): confidence from the nearest competitor.
using Candidates = std::vector<std::vector<std::pair<int, double>>>;  // (index, e) lists.

int Find(std::vector<int>* parent, int i) {
  while ((*parent)[i] != i) i = (*parent)[i] = (*parent)[(*parent)[i]];
  return i;
}

// Matches one group of markers and points (linked by candidate pairs) exactly.
void MatchGroup(const std::vector<int>& markers, const std::vector<int>& points, const Candidates& by_marker,
                GatedAssignment* result, std::vector<double>* margin) {
  if (markers.size() == 1 && points.size() == 1) {
    result->point_of_marker[markers[0]] = points[0];
    return;
  }
  const size_t rows = markers.size(), np = points.size();
  std::vector<std::vector<double>> cost(rows, std::vector<double>(np + rows, 1.0));
  for (size_t r = 0; r < rows; ++r) {
    std::fill(cost[r].begin(), cost[r].begin() + np, kForbidden);
    for (const auto& [k, e] : by_marker[markers[r]]) {
      const size_t c = std::find(points.begin(), points.end(), k) - points.begin();
      cost[r][c] = e * e;
    }
  }
  const auto total = [&](const std::vector<int>& column) {
    double sum = 0.0;
    for (size_t r = 0; r < rows; ++r) sum += column[r] >= 0 ? cost[r][column[r]] : kForbidden;
    return sum;
  };
  const std::vector<int> column = MinimumCostAssignment(cost);
  const double best = total(column);
  for (size_t r = 0; r < rows; ++r) {
    const int c = column[r];
    if (c < 0 || static_cast<size_t>(c) >= np || cost[r][c] >= kForbidden) continue;
    result->point_of_marker[markers[r]] = points[c];
    if (rows > kMarginRows) continue;
    // The margin: what the group's best matching costs more without this pair.
    const double kept = cost[r][c];
    cost[r][c] = kForbidden;
    (*margin)[markers[r]] = std::max(0.0, total(MinimumCostAssignment(cost)) - best);
    cost[r][c] = kept;
  }
}

int Nearest(const std::vector<std::pair<int, double>>& list) {
  int best = -1;
  double best_e = std::numeric_limits<double>::infinity();
  for (const auto& [i, e] : list) {
    if (e < best_e) best = i, best_e = e;
  }
  return best;
}

// Confidence and conflict of each marker once the matches are made.
void ScoreMatches(const Candidates& by_marker, const Candidates& by_point, const std::vector<double>& margin,
                  GatedAssignment* result) {
  const int num_markers = static_cast<int>(by_marker.size());
  for (int m = 0; m < num_markers; ++m) {
    if (by_marker[m].empty()) continue;
    const int nearest = Nearest(by_marker[m]);
    const int k = result->point_of_marker[m];
    bool conflict = k != nearest;
    for (int n = 0; n < num_markers && !conflict; ++n) {
      conflict = n != m && !by_marker[n].empty() && Nearest(by_marker[n]) == nearest;
    }
    result->conflict[m] = conflict;
    if (k < 0) continue;
    double e = 0.0, e_alt = std::numeric_limits<double>::infinity();
    for (const auto& [i, ei] : by_marker[m]) {
      if (i == k) e = ei;
      else e_alt = std::min(e_alt, ei);
    }
    for (const auto& [n, en] : by_point[k]) {
      if (n != m) e_alt = std::min(e_alt, en);
    }
    if (margin[m] >= 0.0) e_alt = std::sqrt(e * e + margin[m]);
    result->confidence[m] = (1.0 - e * e) * std::max(0.0, 1.0 - e / e_alt);
  }
}

}  // namespace

void AssignGated(const std::vector<Eigen::Vector3d>& predicted, const std::vector<double>& gate,
                 const std::vector<Eigen::Vector3d>& points, GatedAssignment* result) {
  const int num_markers = static_cast<int>(predicted.size());
  const int num_points = static_cast<int>(points.size());
  result->point_of_marker.assign(num_markers, -1);
  result->confidence.assign(num_markers, 0.0);
  result->distance.assign(num_markers, std::numeric_limits<double>::quiet_NaN());
  result->conflict.assign(num_markers, false);
  Candidates by_marker(num_markers), by_point(num_points);
  std::vector<double> margin(num_markers, -1.0);  // Of each match in a group of more than one pair.
  std::vector<int> parent(num_markers + num_points);
  std::iota(parent.begin(), parent.end(), 0);
  for (int m = 0; m < num_markers; ++m) {
    if (!predicted[m].allFinite() || !(gate[m] > 0.0)) continue;
    const double g2 = gate[m] * gate[m];
    for (int k = 0; k < num_points; ++k) {
      const double d2 = (points[k] - predicted[m]).squaredNorm();
      if (!(d2 < g2)) continue;
      const double e = std::sqrt(d2) / gate[m];
      by_marker[m].push_back({k, e});
      by_point[k].push_back({m, e});
      parent[Find(&parent, m)] = Find(&parent, num_markers + k);
    }
  }
  std::vector<std::vector<int>> group_markers(num_markers + num_points), group_points(num_markers + num_points);
  for (int m = 0; m < num_markers; ++m) {
    if (!by_marker[m].empty()) group_markers[Find(&parent, m)].push_back(m);
  }
  for (int k = 0; k < num_points; ++k) {
    if (!by_point[k].empty()) group_points[Find(&parent, num_markers + k)].push_back(k);
  }
  for (size_t g = 0; g < group_markers.size(); ++g) {
    if (!group_markers[g].empty()) MatchGroup(group_markers[g], group_points[g], by_marker, result, &margin);
  }
  ScoreMatches(by_marker, by_point, margin, result);
  for (int m = 0; m < num_markers; ++m) {
    const int k = result->point_of_marker[m];
    if (k >= 0) result->distance[m] = (points[k] - predicted[m]).norm();
  }
}

}  // namespace mocapsolve
