#include "problems/edit_propagation/pose_kernel.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <Eigen/Eigenvalues>
#include <glog/logging.h>
#include <nanoflann.hpp>

namespace mocapsolve {

namespace {

// Columns: the frames' coordinates on the leading principal axes of the pose vectors
// (at most kSearchDims, enough for 99.9% of the variance), centred.
constexpr int kSearchDims = 12;
Eigen::MatrixXd SearchCoordinates(const Eigen::MatrixXd& features) {
  const Eigen::MatrixXd centred = features.rowwise() - features.colwise().mean();
  if (features.cols() <= kSearchDims) return centred.transpose();
  const Eigen::MatrixXd covariance = centred.transpose() * centred;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
  const Eigen::Index d = features.cols();
  const double total = std::max(solver.eigenvalues().sum(), 1e-300);
  int r = 0;
  double kept = 0.0;
  while (r < kSearchDims && kept < 0.999 * total) kept += solver.eigenvalues()[d - 1 - r++];
  r = std::max(r, 1);
  return (centred * solver.eigenvectors().rightCols(r)).transpose();
}

}  // namespace

std::vector<std::vector<GraphEdge>> PoseNeighbourGraph(const Eigen::MatrixXd& features, int knn) {
  CHECK_GE(knn, 1);
  const int n = static_cast<int>(features.rows());
  std::vector<std::vector<int>> sets(n);
  if (n > 1) {
    // Candidates from a kd-tree in the principal subspace, reranked by the full distance.
    const Eigen::MatrixXd points = SearchCoordinates(features);  // One column per frame.
    const bool projected = points.rows() < features.cols();
    const int k = std::min(knn + 1, n);  // The query frame finds itself too.
    const int candidates = projected ? std::min(2 * k, n) : k;
    using Tree = nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixXd, -1, nanoflann::metric_L2,
                                                     /*row_major=*/false>;
    Tree tree(static_cast<Tree::Dimension>(points.rows()), std::cref(points), 16);
    std::vector<Eigen::Index> indices(candidates);
    std::vector<double> squared(candidates);
    std::vector<std::pair<double, int>> ranked;
    for (int i = 0; i < n; ++i) {
      nanoflann::KNNResultSet<double, Eigen::Index> result(candidates);
      result.init(indices.data(), squared.data());
      tree.index->findNeighbors(result, points.col(i).data(), nanoflann::SearchParams());
      const int found = static_cast<int>(result.size());
      ranked.clear();
      for (int r = 0; r < found; ++r) {
        const int j = static_cast<int>(indices[r]);
        if (j == i) continue;
        ranked.emplace_back(projected ? (features.row(i) - features.row(j)).squaredNorm() : squared[r], j);
      }
      const int keep = std::min<int>(knn, static_cast<int>(ranked.size()));
      std::partial_sort(ranked.begin(), ranked.begin() + keep, ranked.end());
      for (int r = 0; r < keep; ++r) {
        sets[i].push_back(ranked[r].second);
        sets[ranked[r].second].push_back(i);
      }
      if (i + 1 < n) {
        sets[i].push_back(i + 1);
        sets[i + 1].push_back(i);
      }
    }
  }
  std::vector<std::vector<GraphEdge>> graph(n);
  for (int i = 0; i < n; ++i) {
    std::vector<int>& s = sets[i];
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
    graph[i].reserve(s.size());
    for (int j : s) graph[i].push_back({j, (features.row(i) - features.row(j)).norm()});
  }
  return graph;
}

Eigen::MatrixXd DensePoseKernel(const Eigen::MatrixXd& features, double sigma) {
  CHECK_GT(sigma, 0.0);
  const Eigen::Index n = features.rows();
  // |a - b|^2 = |a|^2 + |b|^2 - 2 a.b, clamped at 0 against round-off.
  const Eigen::VectorXd norms = features.rowwise().squaredNorm();
  Eigen::MatrixXd k = -2.0 * features * features.transpose();
  k.colwise() += norms;
  k.rowwise() += norms.transpose();
  const double scale = -1.0 / (2.0 * sigma * sigma);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < n; ++i) k(i, j) = std::exp(scale * std::max(0.0, k(i, j)));
    k(j, j) = 1.0;
  }
  return k;
}

Eigen::SparseMatrix<double> SparsePoseKernel(const std::vector<std::vector<GraphEdge>>& graph,
                                             double sigma) {
  CHECK_GT(sigma, 0.0);
  const int n = static_cast<int>(graph.size());
  const double scale = -1.0 / (2.0 * sigma * sigma);
  std::vector<Eigen::Triplet<double>> triplets;
  size_t edges = 0;
  for (const auto& row : graph) edges += row.size();
  triplets.reserve(edges + n);
  for (int i = 0; i < n; ++i) {
    triplets.emplace_back(i, i, 1.0);
    for (const GraphEdge& e : graph[i]) {
      triplets.emplace_back(i, e.neighbour,
                            std::max(1e-300, std::exp(scale * e.distance * e.distance)));
    }
  }
  Eigen::SparseMatrix<double> k(n, n);
  k.setFromTriplets(triplets.begin(), triplets.end());
  return k;
}

}  // namespace mocapsolve
