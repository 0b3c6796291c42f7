#include "problems/marker_repair/unlabelled_assignment.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glog/logging.h>

namespace mocapsolve {
namespace {
const Eigen::Vector3d kNan = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
}  // namespace

std::vector<int> MinimumCostAssignment(const std::vector<std::vector<double>>& cost) {
  const int n = static_cast<int>(cost.size());
  if (n == 0) return {};
  const int m = static_cast<int>(cost[0].size());
  CHECK_LE(n, m) << "MinimumCostAssignment: more rows than columns";
  const double inf = std::numeric_limits<double>::infinity();
  // Potentials u (rows), v (columns); p[j]: the row matched to column j (1-based, 0 =
  // none; column 0 is the virtual start of each augmenting path).
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0), min_slack(m + 1);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);
  std::vector<char> used(m + 1);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::fill(min_slack.begin(), min_slack.end(), inf);
    std::fill(used.begin(), used.end(), 0);
    do {
      used[j0] = 1;
      const int i0 = p[j0];
      int j1 = 0;
      double delta = inf;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double slack = cost[i0 - 1][j - 1] - u[i0] - v[j];
        if (slack < min_slack[j]) min_slack[j] = slack, way[j] = j0;
        if (min_slack[j] < delta) delta = min_slack[j], j1 = j;
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          min_slack[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> column(n, -1);
  for (int j = 1; j <= m; ++j) {
    if (p[j] != 0) column[p[j] - 1] = j - 1;
  }
  return column;
}

std::vector<UnlabelledAssignment> AssignUnlabelledPoints(const MarkerResidualModel& model,
                                                         const UnlabelledPoints& unlabelled,
                                                         const UnlabelledAssignmentOptions& options,
                                                         MarkerTrajectories* x) {
  const int nf = x->num_frames(), nm = x->num_markers(), nk = unlabelled.num_tracks();
  std::vector<UnlabelledAssignment> out;
  if (nk == 0 || nf == 0) return out;
  CHECK_EQ(static_cast<int>(unlabelled.points.size()), nf) << "unlabelled points and markers differ in frames";
  std::vector<double> gate(nm), continuity(nm);
  for (int m = 0; m < nm; ++m) {
    gate[m] = std::clamp(model.median_deviation[m] + options.mads * model.scale[m], options.min_distance,
                         std::max(options.min_distance, options.max_distance));
    continuity[m] = std::max(model.step_gate[m], 0.5 * options.min_distance);
  }
  // claim[f][m]: the track whose point marker m takes at frame f, or -1.
  std::vector<std::vector<int>> claim(nf, std::vector<int>(nm, -1));
  constexpr double kForbidden = 1e6;  // Above any sum of allowed costs and "unmatched" ones.
  for (int f = 0; f < nf; ++f) {
    const auto& p = model.predicted[f];
    std::vector<int> points;
    std::vector<double> ghost;  // Per point of `points`: its best ratio to a present marker.
    for (int k = 0; k < nk; ++k) {
      if (!unlabelled.present(f, k)) continue;
      double best = std::numeric_limits<double>::infinity();
      for (int n = 0; n < nm; ++n) {
        if (x->valid(f, n)) best = std::min(best, (unlabelled.points[f][k] - p[n]).norm() / gate[n]);
      }
      points.push_back(k);
      ghost.push_back(best);
    }
    if (points.empty()) continue;
    std::vector<int> rows;
    std::vector<std::vector<double>> ratio;  // [row][point] d / g, or kForbidden.
    for (int m = 0; m < nm; ++m) {
      if (x->valid(f, m)) continue;
      std::vector<double> r(points.size(), kForbidden);
      bool any = false;
      for (size_t i = 0; i < points.size(); ++i) {
        const double q = (unlabelled.points[f][points[i]] - p[m]).norm() / gate[m];
        if (q <= 1.0 && q < ghost[i]) r[i] = q, any = true;
      }
      if (any) rows.push_back(m), ratio.push_back(std::move(r));
    }
    if (rows.empty()) continue;
    // Columns: the points, then one "unmatched" column per row (cost 1 for its own row).
    const size_t nr = rows.size(), np = points.size();
    std::vector<std::vector<double>> cost(nr, std::vector<double>(np + nr, kForbidden));
    for (size_t r = 0; r < nr; ++r) {
      for (size_t i = 0; i < np; ++i) cost[r][i] = ratio[r][i];
      cost[r][np + r] = 1.0;
    }
    const std::vector<int> column = MinimumCostAssignment(cost);
    for (size_t r = 0; r < nr; ++r) {
      const int c = column[r];
      if (c >= 0 && static_cast<size_t>(c) < np && ratio[r][c] < kForbidden) claim[f][rows[r]] = points[c];
    }
  }
  // Runs of one track on one marker, split where the point's step is continuous neither
  // with the prediction's nor with the track's own previous step; kept by continuity with
  // the marker's observed samples beside them.
  auto continuous_step = [&](int m, int f, const Eigen::Vector3d& at_f, const Eigen::Vector3d& at_previous,
                             const Eigen::Vector3d& before_previous) {
    const Eigen::Vector3d step = at_f - at_previous;
    if ((step - (model.predicted[f][m] - model.predicted[f - 1][m])).norm() <= continuity[m]) return true;
    return before_previous.allFinite() && (step - (at_previous - before_previous)).norm() <= continuity[m];
  };
  std::vector<std::pair<int, Eigen::Vector3d>> writes;  // (frame, point) per marker.
  for (int m = 0; m < nm; ++m) {
    writes.clear();
    for (int f = 0; f < nf;) {
      const int k = claim[f][m];
      if (k < 0) { ++f; continue; }
      const int a = f;
      // The marker's track before the run, then the run's points: frame g's sample, or NaN.
      int b = a;
      auto along = [&](int g) -> Eigen::Vector3d {
        if (g >= a && g <= b) return unlabelled.points[g][k];
        if (g >= 0 && g < a && x->valid(g, m)) return x->position(g, m);
        return kNan;
      };
      while (b + 1 < nf && claim[b + 1][m] == k &&
             continuous_step(m, b + 1, unlabelled.points[b + 1][k], along(b), along(b - 1))) {
        ++b;
      }
      f = b + 1;
      bool continuous = false, broken = false;
      if (a > 0 && x->valid(a - 1, m)) {
        const bool ok = continuous_step(m, a, along(a), along(a - 1), along(a - 2));
        continuous |= ok, broken |= !ok;
      }
      if (b + 1 < nf && x->valid(b + 1, m)) {
        const bool ok = continuous_step(m, b + 1, x->position(b + 1, m), along(b), along(b - 1));
        continuous |= ok, broken |= !ok;
      }
      if (broken || (!continuous && b - a + 1 < options.min_frames)) continue;
      UnlabelledAssignment assignment;
      assignment.marker = m;
      assignment.track = k;
      assignment.first = a;
      assignment.last = b;
      for (int g = a; g <= b; ++g) {
        assignment.mean_distance += (unlabelled.points[g][k] - model.predicted[g][m]).norm();
        writes.emplace_back(g, unlabelled.points[g][k]);
      }
      assignment.mean_distance /= (b - a + 1);
      out.push_back(assignment);
    }
    for (const auto& [g, point] : writes) x->SetSample(g, m, point);
  }
  return out;
}

}  // namespace mocapsolve
