#include "problems/retarget/vertex_subsampling.h"

#include <algorithm>
#include <limits>

#include <glog/logging.h>
#include <nanoflann.hpp>

namespace mocapsolve {
namespace {

using KdTree =
    nanoflann::KDTreeEigenMatrixAdaptor<Eigen::Matrix3Xd, 3, nanoflann::metric_L2_Simple, false>;

// Farthest-point sampling: adds `count` vertices of `candidates` to *picked, each the one
// farthest from everything picked so far (*distance holds that distance, squared, for
// every vertex and is kept up to date).
void FarthestPoints(const Eigen::Matrix3Xd& positions, const std::vector<int>& candidates,
                    int count, std::vector<double>* distance, std::vector<int>* picked) {
  for (int n = 0; n < count; ++n) {
    int best = -1;
    double best_distance = -1.0;
    for (int i : candidates) {
      if ((*distance)[i] > best_distance) {
        best_distance = (*distance)[i];
        best = i;
      }
    }
    if (best < 0 || best_distance <= 0.0) return;  // All candidates picked (or coincident).
    picked->push_back(best);
    const Eigen::Vector3d p = positions.col(best);
    for (int i = 0; i < positions.cols(); ++i) {
      (*distance)[i] = std::min((*distance)[i], (positions.col(i) - p).squaredNorm());
    }
  }
}

// At least `quota` samples among the vertices of each group (group[i] in [0, num_groups), -1
// none) that has vertices: farthest-point samples among the group's own vertices, measured
// from its samples only (so they spread over its region), eligible ones first, then any.
void AddQuota(const Eigen::Matrix3Xd& positions, const std::vector<bool>& eligible, const std::vector<int>& group,
              int num_groups, int quota, std::vector<int>* picked) {
  const int nv = static_cast<int>(positions.cols());
  std::vector<int> count(num_groups, 0);
  for (int i : *picked) {
    if (group[i] >= 0) ++count[group[i]];
  }
  std::vector<std::vector<int>> members(num_groups);
  for (int i = 0; i < nv; ++i) {
    if (group[i] >= 0) members[group[i]].push_back(i);
  }
  for (int g = 0; g < num_groups; ++g) {
    if (count[g] >= quota || members[g].empty()) continue;
    std::vector<int> own_eligible;
    for (int i : members[g]) {
      if (eligible[i]) own_eligible.push_back(i);
    }
    std::vector<double> own_distance(nv, std::numeric_limits<double>::infinity());
    for (int s : *picked) {
      if (group[s] != g) continue;
      for (int i : members[g]) {
        own_distance[i] = std::min(own_distance[i], (positions.col(i) - positions.col(s)).squaredNorm());
      }
    }
    for (int s : *picked) own_distance[s] = 0.0;
    const int before = static_cast<int>(picked->size());
    FarthestPoints(positions, own_eligible, quota - count[g], &own_distance, picked);
    const int added = static_cast<int>(picked->size()) - before;
    if (count[g] + added < quota) {
      FarthestPoints(positions, members[g], quota - count[g] - added, &own_distance, picked);
    }
  }
}

}  // namespace

int DominantJoint(const SkinnedMesh& mesh, int vertex) {
  int best = -1;
  double best_weight = -1.0;
  for (int k = mesh.weight_begin(vertex); k < mesh.weight_end(vertex); ++k) {
    const int j = mesh.weight_joint(k);
    if (mesh.weight(k) > best_weight || (mesh.weight(k) == best_weight && j < best)) {
      best_weight = mesh.weight(k);
      best = j;
    }
  }
  return best;
}

std::vector<int> SubsampleVertices(const SkinnedMesh& mesh, const Eigen::Matrix3Xd& positions,
                                   const Eigen::Matrix3Xd& normals,
                                   const SubsampleOptions& options, const std::vector<int>& parts) {
  const int nv = mesh.num_vertices();
  CHECK_EQ(positions.cols(), nv);
  CHECK_EQ(normals.cols(), nv);
  CHECK_GE(options.ratio, 1);
  std::vector<int> picked;
  if (nv == 0) return picked;

  // 1. Normal check against the neighbours' mean normal.
  std::vector<bool> eligible(nv, true);
  const int k = std::min(options.neighbours + 1, nv);
  if (k > 1) {
    KdTree tree(3, std::cref(positions), 10);
    std::vector<Eigen::Index> index(k);
    std::vector<double> distance(k);
    for (int i = 0; i < nv; ++i) {
      const Eigen::Vector3d p = positions.col(i);
      const size_t found = tree.index->knnSearch(p.data(), k, index.data(), distance.data());
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (size_t n = 0; n < found; ++n) {
        if (index[n] != i) mean += normals.col(index[n]);
      }
      const double norm = mean.norm();
      eligible[i] = norm > 1e-12 &&
                    1.0 - normals.col(i).dot(mean / norm) <= options.normal_threshold;
    }
  }

  // 2. Farthest-point sampling over the eligible vertices.
  std::vector<int> candidates;
  for (int i = 0; i < nv; ++i) {
    if (eligible[i]) candidates.push_back(i);
  }
  if (candidates.empty()) {  // Nothing passes the check: sample the whole mesh.
    for (int i = 0; i < nv; ++i) candidates.push_back(i);
  }
  const int target = std::max(1, nv / options.ratio);
  std::vector<double> distance(nv, std::numeric_limits<double>::infinity());
  int first = options.first;
  if (first < 0 || first >= nv || (!eligible[first] && !candidates.empty())) first = candidates[0];
  picked.push_back(first);
  for (int i = 0; i < nv; ++i) distance[i] = (positions.col(i) - positions.col(first)).squaredNorm();
  FarthestPoints(positions, candidates, target - 1, &distance, &picked);

  // 3. At least min_per_joint samples per dominating joint, then min_per_part per part.
  std::vector<int> dominant(nv);
  for (int i = 0; i < nv; ++i) dominant[i] = DominantJoint(mesh, i);
  AddQuota(positions, eligible, dominant, mesh.num_joints(), options.min_per_joint, &picked);
  if (!parts.empty()) {
    CHECK_EQ(static_cast<int>(parts.size()), nv);
    const int num_parts = *std::max_element(parts.begin(), parts.end()) + 1;
    AddQuota(positions, eligible, parts, num_parts, options.min_per_part, &picked);
  }
  return picked;
}

}  // namespace mocapsolve
