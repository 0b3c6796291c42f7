// Pose kernel: the similarity graph of a clip's pose vectors (Dean et al. 2018, eq. 1).
//
// features: #frames x D pose vectors (pose_features.h). The Gaussian kernel is
//
//   K_ij = exp(-|p_i - p_j|^2 / (2 sigma^2)),  K_ii = 1.
//
// Dense: all pairs. Sparse: the k-nearest-neighbour graph (each frame's `knn` nearest
// other frames by Euclidean pose distance, found with a nanoflann kd-tree, plus the
// temporal neighbours i-1 and i+1 so a clip is always one connected chain), symmetrized
// (j in N(i) or i in N(j)), with K on its edges and 1 on the diagonal. Kernel values are
// floored at 1e-300 on graph edges so that the chain never breaks numerically.
// The neighbour search is approximate for D > 12: a nanoflann kd-tree over the pose
// vectors' leading principal components (at most 12, or fewer holding 99.9% of the
// variance) proposes 2 (knn + 1) candidates per frame, reranked by the full distance
// (recall of the exact knn = 10 neighbours on CMU 16_15: 0.9998).
// Exact for D <= 12.
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_POSE_KERNEL_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_POSE_KERNEL_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace mocapsolve {

struct GraphEdge {
  int neighbour = 0;
  double distance = 0.0;  // |p_i - p_neighbour|, pose-vector units.
};

// Per frame: its symmetrized neighbours (knn nearest + temporal), sorted by index, no self.
// knn >= 1 (clamped to #frames - 1).
std::vector<std::vector<GraphEdge>> PoseNeighbourGraph(const Eigen::MatrixXd& features, int knn);

Eigen::MatrixXd DensePoseKernel(const Eigen::MatrixXd& features, double sigma);
Eigen::SparseMatrix<double> SparsePoseKernel(const std::vector<std::vector<GraphEdge>>& graph,
                                             double sigma);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_POSE_KERNEL_H_
