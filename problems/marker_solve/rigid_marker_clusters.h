// Rigid marker clusters: markers that move rigidly together over a take, found from the
// data alone (no labels), as the first step of associating an unknown protocol's markers
// with body segments (marker_association.h).
//
// Spread. For markers a, b and the sampled frames F_ab where both are observed, the
// distances d_ab(f) = |x_a(f) - x_b(f)|, f in F_ab. Their spread is the robust standard
// deviation s_ab = (q90 - q10) / 2.563 of d_ab over F_ab (a few swapped or ghost samples do
// not inflate it; a joint that bends in a tenth of the take does), and their typical distance the median m_ab. Pairs seen
// together in fewer than `min_covisible_frames` frames get s_ab = +inf (no evidence).
// Two markers on one segment keep their distance (s of a few mm, skin motion); markers on
// two segments that a joint connects change it as the joint moves (unless the take holds
// that joint still: then the segments are one cluster, which the association copes with).
//
// Clustering. Agglomerative, average linkage: start from singletons and merge the two
// clusters with the smallest mean spread over their cross pairs while it is below
// `max_spread` and no cross pair is farther apart than `max_extent` (the typical
// distance m_ab: a segment is smaller than that, so two hands held still on one bar do not
// merge). Pairs without evidence count as +inf in the mean (they block the merge).
// Lengths in the trajectories' units, scaled by `metres_per_unit` into metres.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_RIGID_MARKER_CLUSTERS_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_RIGID_MARKER_CLUSTERS_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_trajectories.h"

namespace mocapsolve {

struct RigidClusterOptions {
  int max_frames = 400;           // Frames sampled evenly over the take.
  int min_covisible_frames = 10;  // Fewer: no evidence for the pair.
  double max_spread = 0.004;      // Metres: the largest mean spread of a merge.
  double max_extent = 0.55;       // Metres: the largest typical distance inside a cluster.
};

// #M by #M matrices, metres; the diagonal is 0.
struct PairwiseSpread {
  Eigen::MatrixXd spread;    // s_ab (+inf without evidence).
  Eigen::MatrixXd distance;  // m_ab (NaN without evidence).
};

// `markers`: the indices of `take` to use (others ignored); the matrices are over them, in
// that order.
PairwiseSpread ComputePairwiseSpread(const MarkerTrajectories& take, const std::vector<int>& markers,
                                     double metres_per_unit, const RigidClusterOptions& options);

// Clusters as lists of indices into the spread matrices, largest first.
std::vector<std::vector<int>> ClusterRigidMarkers(const PairwiseSpread& pairs, const RigidClusterOptions& options);

// The mean spread between two clusters (+inf when a pair lacks evidence), and the smallest
// spread of any cross pair (two segments a joint connects hold a marker near the joint at
// a nearly constant distance from the other's).
double MeanClusterSpread(const PairwiseSpread& pairs, const std::vector<int>& a, const std::vector<int>& b);
double MinClusterSpread(const PairwiseSpread& pairs, const std::vector<int>& a, const std::vector<int>& b);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_RIGID_MARKER_CLUSTERS_H_
