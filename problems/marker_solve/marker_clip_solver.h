// Whole-clip marker solving: all frames as one sparse least-squares problem.
//
//   minimize  sum_f sum_{m observed at f} rho(|MarkerResidual_fm|^2)
//           + sum_f sum_j |FiniteDifferenceResidual(q_j over frames f.. f+order)|^2
//           + sum_f |FiniteDifferenceResidual(root translation over frames)|^2
//
// Unknowns per frame: the root translation and the rotation of every joint that moves a
// marker (as in MarkerFrameSolver). Smoothness is the velocity (first difference) or the
// acceleration (second difference) of each series between consecutive frames, weighted
// per radian for rotations and per skeleton unit for the root translation. The weights
// act on per-frame differences, so the same weight smooths more at a higher capture rate
// (where true per-frame differences are smaller).
//
// Solved by Ceres with SPARSE_NORMAL_CHOLESKY (Eigen's sparse LDLT by default;
// --sparse_library=suite_sparse for CHOLMOD). The motion given
// is the initial guess (e.g. per-frame solutions) and receives the result.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_CLIP_SOLVER_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_CLIP_SOLVER_H_

#include <string>
#include <vector>

#include <ceres/solver.h>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_solve/finite_difference_residual.h"

namespace mocapsolve {

struct ClipSolveOptions {
  double marker_weight = 1.0;
  std::string loss = "none";   // none | huber | cauchy
  double loss_scale = 1.0;     // Skeleton units.
  // Velocity keeps the normal equations block-tridiagonal (half the band of
  // acceleration, about 3x faster to factor); acceleration preserves speed better.
  SmoothnessOrder smoothness_order = SmoothnessOrder::kVelocity;
  double rotation_smoothness = 1.0;     // Weight of a joint's finite difference, per radian.
  double translation_smoothness = 1.0;  // Weight of the root's, per skeleton unit.
  ceres::Solver::Options ceres;

  bool IsValid(std::string* error) const;
};

// SPARSE_NORMAL_CHOLESKY on Eigen's sparse LDLT, Levenberg-Marquardt, silent.
ceres::Solver::Options DefaultClipCeresOptions();

struct ClipSolveReport {
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int iterations = 0;
  bool usable = false;
  int residual_blocks = 0;
  int parameters = 0;          // Tangent dimension of the problem.
  double rms_marker_error = 0.0;  // Over all observed samples, skeleton units.
  double solve_seconds = 0.0;
  std::string brief;
  std::string full;            // Ceres' FullReport().
};

// observed[f][m]: marker m of the marker set at frame f (skeleton units, non-finite =
// missing); motion->frames.size() must equal observed.size().
Status SolveClip(const Skeleton& skeleton, const MarkerSet& markers,
                 const std::vector<std::vector<Eigen::Vector3d>>& observed,
                 const ClipSolveOptions& options, Motion* motion, ClipSolveReport* report);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_CLIP_SOLVER_H_
