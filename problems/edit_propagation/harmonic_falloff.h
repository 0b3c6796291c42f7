// Harmonic falloff: an edit's weight field as the harmonic function on the pose graph
// (Zhu, Ghahramani & Lafferty 2003), solved as a sparse least-squares problem by Ceres.
//
//   minimize  1/2 sum_{edges (i, j)} K_ij (u_i - u_j)^2       (HarmonicEdgeResidual)
//   subject to u_l = y_l at the labelled frames l (parameter blocks held constant)
//
// over one scalar u per frame. K_ij is the Gaussian pose kernel (Dean et al. 2018, eq. 1)
// on the edges of the symmetrized kNN graph of the pose vectors plus the temporal
// neighbours (pose_kernel.h, PoseNeighbourGraph), so the graph of a clip is connected. The
// optimum solves L_FF u_F = -L_FL y_L with L = D - K the unnormalized graph Laplacian: each
// free u_i is the K-weighted mean of its neighbours, so 0 <= u <= 1 when the labels are 0
// or 1 (maximum principle), and the field follows the motion's own geometry: it reaches
// every frame similar to the edited one (the other strides of a walk) through the kNN
// edges, and decays toward dissimilar poses.
//
// Optionally a ground node labelled 0 is linked to every frame with kernel K_g
// (HarmonicOptions::ground_weight): the screened energy E + 1/2 K_g sum_i u_i^2.
//
// Labels of an edit at frame i: u_i = 1, u = 0 at the other edited frames (each edit gets
// its own field, so at its own frame only its delta is applied, see pose_edit.h) and at the
// anchors (`mocapsolve propagate` labels the ends of --region where it cuts the clip, and
// the clip's ends too without a ground node: a harmonic function with a single label and
// no ground is the constant 1). Frames outside the region are not in the graph and get weight 0.
//
// The problem is linear; Levenberg-Marquardt with a huge initial trust region (negligible
// damping) solves it in one Gauss-Newton step, by SPARSE_NORMAL_CHOLESKY on Eigen's sparse
// LDLT (or CHOLMOD). One Problem serves all fields of a clip: only the labelled values
// change between solves.
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_HARMONIC_FALLOFF_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_HARMONIC_FALLOFF_H_

#include <string>
#include <utility>
#include <vector>

#include <ceres/types.h>
#include <Eigen/Core>

#include "kinematics/status.h"

namespace mocapsolve {

// An undirected graph edge between frames a and b (a != b) with kernel value K >= 0.
struct WeightedEdge {
  int a = 0;
  int b = 0;
  double kernel = 0.0;
};

// Edges of the symmetrized kNN + temporal graph of `features` (#frames x D pose vectors,
// pose_features.h), each once (a < b), weighted exp(-|p_a - p_b|^2 / (2 sigma^2))
// floored at 1e-300 so the temporal chain never breaks numerically. sigma > 0; knn >= 1.
std::vector<WeightedEdge> PoseGraphEdges(const Eigen::MatrixXd& features, int knn, double sigma);

struct HarmonicOptions {
  // Kernel weight K_g of an edge from every frame to a "ground" node labelled 0 (the
  // absorbing node of Zhu et al.'s random-walk reading: at each step the walk is absorbed
  // with probability K_g / (degree + K_g)), so the field decays away from the edit instead
  // of spreading almost evenly when the only 0 labels are far away. 0 = off (pure harmonic).
  double ground_weight = 0.0;
  ceres::SparseLinearAlgebraLibraryType sparse_library = ceres::EIGEN_SPARSE;
  int max_iterations = 10;
  int num_threads = 1;
  bool IsValid(std::string* error) const;
};

struct HarmonicReport {
  int frames = 0;
  int edges = 0;
  int fields = 0;
  int iterations = 0;          // Summed over fields.
  double solve_seconds = 0.0;  // Summed over fields (Ceres' total time).
  double max_gradient = 0.0;   // Largest |dE/du| over free frames at the solutions.
  bool usable = true;
  std::string brief;           // Ceres' BriefReport of the last field.
};

// One field per labelling: labels[k] lists (frame, value) pairs; (*fields)[k] has
// num_frames values (labelled frames exactly their value; frames unreachable from any
// label stay 0). Errors: bad frame indices or edges, no labels, a failed solve.
Status SolveHarmonicFields(int num_frames, const std::vector<WeightedEdge>& edges,
                           const std::vector<std::vector<std::pair<int, double>>>& labels,
                           const HarmonicOptions& options, std::vector<Eigen::VectorXd>* fields,
                           HarmonicReport* report);

// The falloffs of edits at `edited_frames`: field k has u = 1 at edited_frames[k], 0 at
// the other edited frames and at `anchors` (anchors that are edited frames are skipped).
Status HarmonicFalloffs(int num_frames, const std::vector<WeightedEdge>& edges,
                        const std::vector<int>& edited_frames, const std::vector<int>& anchors,
                        const HarmonicOptions& options, std::vector<Eigen::VectorXd>* fields,
                        HarmonicReport* report);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_HARMONIC_FALLOFF_H_
