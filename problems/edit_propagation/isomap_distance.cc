#include "problems/edit_propagation/isomap_distance.h"

#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include <glog/logging.h>

namespace mocapsolve {

Eigen::VectorXd GeodesicDistances(const std::vector<std::vector<GraphEdge>>& graph, int source) {
  const int n = static_cast<int>(graph.size());
  CHECK(source >= 0 && source < n);
  Eigen::VectorXd d = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  d[source] = 0.0;
  queue.emplace(0.0, source);
  while (!queue.empty()) {
    const auto [dist, i] = queue.top();
    queue.pop();
    if (dist > d[i]) continue;
    for (const GraphEdge& e : graph[i]) {
      const double candidate = dist + e.distance;
      if (candidate < d[e.neighbour]) {
        d[e.neighbour] = candidate;
        queue.emplace(candidate, e.neighbour);
      }
    }
  }
  return d;
}

}  // namespace mocapsolve
