// ISOMAP distance (Tenenbaum et al. 2000), the magic-wand paper's second comparison:
// the geodesic distance from one frame to every other along the pose neighbour graph
// (pose_kernel.h: knn nearest poses plus temporal neighbours, Euclidean edge lengths in
// pose-vector units), by Dijkstra's algorithm. This is the distance ISOMAP's classical MDS
// step embeds; we use it directly (no MDS), so it is exact on the graph and O(E log V)
// per source frame.
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_ISOMAP_DISTANCE_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_ISOMAP_DISTANCE_H_

#include <vector>

#include <Eigen/Core>

#include "problems/edit_propagation/pose_kernel.h"

namespace mocapsolve {

// #frames geodesic distances from `source` (0 there; +infinity where unreachable).
Eigen::VectorXd GeodesicDistances(const std::vector<std::vector<GraphEdge>>& graph, int source);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_ISOMAP_DISTANCE_H_
