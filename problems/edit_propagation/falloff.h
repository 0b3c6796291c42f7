// Falloff: the data-driven region of influence of an edit at one frame (Dean, Lewis and
// Chalmers 2018, "magic wand", sections 3.1-3.3, and its comparisons in section 4).
//
// Pose vectors p_i (pose_features.h: concatenated log-quaternion joint rotations, one row
// per frame) give a Gaussian kernel and a normalized graph Laplacian
//
//   K_ij = exp(-|p_i - p_j|^2 / (2 sigma^2))            (eq. 1)
//   A = D^-1/2 K D^-1/2,  D = diag(row sums of K)       (eq. 2)
//   L = I - A,  L phi_k = lambda_k phi_k,  0 = lambda_0 <= lambda_1 <= ...
//
// and the Green's function of L (eq. 3), summed over the nonzero eigenvalues:
//
//   G_ij = sum_{k>0} phi_k(i) phi_k(j) / lambda_k.
//
// With all terms G is exactly the Moore-Penrose pseudo-inverse L^+ of the symmetric L
// (phi_k are the orthonormal eigenvectors of L itself; nothing is rescaled by D^1/2);
// with `eigenpairs` = m only the m smallest nonzero eigenvalues are kept. The full sum is
// dominated by its diagonal (lambda_k near 1 for most k) and barely reaches the other
// strides of a walk, so the default is a truncated sum (m = 10) with a wide kernel.
//
// sigma: 0 selects sigma = sigma_scale * (median over frames of |p_{i+1} - p_i|), with
// sigma_scale = 4 by default. Chosen on CMU 16_15 (edits at frames 100, 200, 300; scale
// 2, 3, 4, 6 x m = 5, 10, 20): scale 4 with m = 5-20 gives weight >= 0.91 at the same
// phase of every other stride and <= 0.28 (m = 10: <= 0.15) at the opposite phase; scale
// 2 breaks the graph apart, 3 leaves ~0.5 at the opposite phase, 6 with m = 20 drops the
// same phase to 0.75. The truncated sum's peak can sit 1-3 frames off the edited frame
// (the paper's "offset of 2-3 frames"), which the clamp turns into a short plateau.
//
// Islands: a run of frames whose poses are far from all others (a data glitch, e.g. a
// finger joint flipping by ~180 degrees for a few frames in CMU 131_01) is nearly a
// separate graph component: lambda_k ~ 1e-11 with phi_k its indicator, and that one term
// would swamp the sum. Eigenvalues <= null_eigenvalue (default 1e-6) are therefore treated
// as the null space, like lambda_0, and left out.
//
// Kernel: dense for short clips; above `sparse_above_frames` (or with kernel = kSparse)
// each frame keeps only its `knn` nearest poses plus its temporal neighbours i-1, i+1
// (symmetrized; pose_kernel.h), and the smallest eigenpairs of L come from Spectra
// (largest of A). This is a thinner kernel than the dense one, so its falloff differs a
// little; knn = 30 still meets the 16_15 criterion above (knn = 10 does not: ~0.5).
//
// Weights (eq. 5's w): row i of G over the region [region_begin, region_end), scaled so
// the edited frame i has weight 1 and the least similar frame in the region weight 0,
// clamped to [0, 1] (a truncated sum can exceed G_ii elsewhere):
//
//   weight_j   = clamp((G_ij - min_region G_i.) / (G_ii - min_region G_i.), 0, 1)
//   distance_j = 1 - weight_j  inside the region; distance 1, weight 0 outside.
//
// (The paper calls the normalized quantity a distance, 0 at the edited pose; the weight
// that multiplies the delta-pose in eq. 5 is 1 minus it, so the edited frame gets the
// whole edit.) The comparison methods produce a distance d_j >= 0 from frame i instead
// and are normalized the same way: distance_j = d_j / max_region d, weight = 1 - distance.
//   kDiffusion: diffusion distance after t = diffusion_steps steps of the random walk
//               P = D^-1 K (Coifman and Lafon 2006), from the same eigenpairs:
//               d_j^2 = sum_{k>0} mu_k^(2t) (psi_k(i) - psi_k(j))^2, mu_k = 1 - lambda_k,
//               psi_k(j) = phi_k(j) / sqrt(pi_j), pi_j = D_jj / sum D (the right
//               eigenvectors of P, normalized in the stationary measure pi); the same
//               `eigenpairs` truncation as kGreen (0 = all). Frames of low degree
//               (poses seen once, e.g. the first frames of 16_15) get large psi and so
//               the largest distance, which then sets the normalization: choose a
//               region without them to compare shapes.
//   kIsomap:    the geodesic distance itself (Dijkstra over the isomap_knn graph with Euclidean
//               edge lengths, temporal neighbours always linked), i.e. the distance that
//               ISOMAP's classical-MDS embedding approximates; no MDS step is done.
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_FALLOFF_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_FALLOFF_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/edit_propagation/pose_features.h"
#include "solvers/laplacian_eigenpairs.h"

namespace mocapsolve {

enum class FalloffMethod { kGreen, kDiffusion, kIsomap };
// "green", "diffusion", "isomap".
bool ParseFalloffMethod(const std::string& text, FalloffMethod* method);
std::string FalloffMethodName(FalloffMethod method);

enum class KernelMode { kAuto, kDense, kSparse };

struct FalloffOptions {
  PoseFeatureOptions features;
  double sigma = 0.0;          // Kernel width in pose-vector units (radians); 0 = auto.
  double sigma_scale = 4.0;    // Auto sigma = sigma_scale * median frame-to-frame distance.
  int eigenpairs = 10;         // Nonzero-eigenvalue terms of eq. 3; 0 = all (dense only).
  int region_begin = 0;        // Frames [region_begin, region_end); -1 = to the end.
  int region_end = -1;
  int diffusion_steps = 10;    // t for kDiffusion (the paper's Fig. 3 uses 10).
  int knn = 30;                // Neighbours per frame of the sparse kernel (10 misses the
                               // other strides of 16_15: same-phase weight ~0.5).
  int isomap_knn = 10;         // Neighbours per frame of the ISOMAP graph.
  KernelMode kernel = KernelMode::kAuto;
  int sparse_above_frames = 1000;  // kAuto: sparse kernel for clips longer than this.
  // Eigenvalues of L at or below this count as the null space and are left out of eq. 3
  // (see "Islands" above).
  double null_eigenvalue = 1e-6;

  // Message names the bad field.
  bool IsValid(std::string* error) const;
};

struct Falloff {
  Eigen::VectorXd distance;  // #frames; in [0, 1] over the region, 0 at the edited frame,
                             // 1 outside the region.
  Eigen::VectorXd weight;    // #frames; 1 - distance, clamped to [0, 1] (0 outside).
  Eigen::VectorXd raw;       // #frames; the unnormalized G row (kGreen) or distance.
  int frame = 0;
  int region_begin = 0, region_end = 0;  // Resolved region.
  double sigma_used = 0.0;
  int eigenpairs_used = 0;   // Nonzero-eigenvalue terms summed (kGreen, kDiffusion).
  bool sparse_used = false;
};

// The reusable part: pose-space Laplacian eigenpairs for one clip. Build once (the cost),
// then each Row() is a #frames x m product (re-propagating a new edit is cheap).
// Immutable after Build; Row/Weights are const and thread-safe.
class GreenFunction {
 public:
  // features: #frames x D pose vectors (PoseFeatures). Fails on < 3 frames, non-finite
  // values or a failed eigensolve (message names the option to change).
  Status Build(const Eigen::MatrixXd& features, const FalloffOptions& options);

  int num_frames() const { return static_cast<int>(degrees_.size()); }
  double sigma_used() const { return sigma_; }
  int eigenpairs_used() const { return static_cast<int>(inverse_eigenvalues_.size()); }
  bool sparse_used() const { return sparse_; }
  const LaplacianEigenpairs& eigenpairs() const { return eigen_; }

  // g = row `frame` of G (eq. 3 over the kept terms); #frames.
  void Row(int frame, Eigen::VectorXd* g) const;
  // Row + normalization over the region (see the header comment) into *falloff.
  void Weights(int frame, int region_begin, int region_end, Falloff* falloff) const;
  // Diffusion distance after `steps` steps from `frame` to every frame; #frames.
  void DiffusionDistance(int frame, int steps, Eigen::VectorXd* d) const;

 private:
  LaplacianEigenpairs eigen_;
  Eigen::VectorXd degrees_;
  Eigen::VectorXd inverse_eigenvalues_;  // 1 / lambda_k of the kept terms.
  Eigen::MatrixXd scaled_vectors_;       // phi_k / lambda_k of the kept terms, #frames x m.
  Eigen::MatrixXd vectors_;              // phi_k of the kept terms, #frames x m.
  int first_kept_ = 1;                   // Column of eigen_ of the first kept term.
  double sigma_ = 0.0;
  bool sparse_ = false;
};

// Resolves region_end = -1 and checks 0 <= begin <= frame < end <= num_frames.
Status ResolveRegion(int num_frames, int frame, int region_begin, int region_end,
                     int* begin, int* end);

// Normalizations shared by the methods (see the header comment); `frame` inside the region.
void FalloffFromSimilarity(const Eigen::VectorXd& similarity, int frame, int region_begin,
                           int region_end, Falloff* falloff);
void FalloffFromDistance(const Eigen::VectorXd& distance, int frame, int region_begin,
                         int region_end, Falloff* falloff);

// The whole pipeline for one edit: features, kernel, eigenpairs, row, weights.
Status ComputeFalloff(const Skeleton& skeleton, const Motion& motion, int frame,
                      FalloffMethod method, const FalloffOptions& options, Falloff* falloff);

// The same for several edits of one clip, building the features, graph and eigenpairs
// once: (*falloffs)[e] is the falloff of frames[e]. Each frame must lie in the region.
Status ComputeFalloffs(const Skeleton& skeleton, const Motion& motion,
                       const std::vector<int>& frames, FalloffMethod method,
                       const FalloffOptions& options, std::vector<Falloff>* falloffs);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_FALLOFF_H_
