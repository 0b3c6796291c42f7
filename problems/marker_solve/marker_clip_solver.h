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
// Two solvers minimize the same residual blocks (BuildClipProblem builds them once):
//   "ceres": Levenberg-Marquardt with SPARSE_NORMAL_CHOLESKY (Eigen's sparse LDLT by
//            default; --sparse_library=suite_sparse for CHOLMOD);
//   "dls":   the generic DLS solver (solvers/dls_solver.h) in a sparse normal form, by
//            default kBlockBanded: J^T J in one dense block per frame (that frame's
//            tangent unknowns, frames in order), block-tridiagonal for velocity and
//            pentadiagonal for acceleration smoothness, factored by BlockBandedCholesky
//            (7/3 n^3 resp. 19/3 n^3 flops per frame, n unknowns per frame). Robust losses
//            by IRLS (sqrt(rho') weights): the same gradient as Ceres, a Gauss-Newton
//            Hessian without Ceres' second-order correction: the same stationary points.
//            Damping and stopping rules: solvers/dls_iterations.h.
// The motion given is the initial guess (e.g. per-frame solutions) and receives the result.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_CLIP_SOLVER_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_CLIP_SOLVER_H_

#include <memory>
#include <string>
#include <vector>

#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_solve/finite_difference_residual.h"
#include "solvers/dls_solver.h"

namespace mocapsolve {

// The DLS path's iteration options: 50 iterations, function tolerance 1e-8 (as the Ceres
// defaults below), adaptive damping from lambda 1e-3.
DlsOptions DefaultClipDlsOptions();

struct ClipSolveOptions {
  std::string solver = "ceres";  // ceres | dls (see above).
  double marker_weight = 1.0;
  std::string loss = "none";   // none | huber | cauchy
  double loss_scale = 1.0;     // Skeleton units.
  // Velocity keeps the normal equations block-tridiagonal (half the band of
  // acceleration, about 3x faster to factor); acceleration preserves speed better.
  SmoothnessOrder smoothness_order = SmoothnessOrder::kVelocity;
  double rotation_smoothness = 1.0;     // Weight of a joint's finite difference, per radian.
  double translation_smoothness = 1.0;  // Weight of the root's, per skeleton unit.
  ceres::Solver::Options ceres;  // solver == "ceres".
  DlsOptions dls = DefaultClipDlsOptions();  // solver == "dls".
  // kBlockBanded (the default) or kSparseLdlt (Eigen's SimplicialLDLT, AMD ordering).
  DlsLinearSolver dls_linear_solver = DlsLinearSolver::kBlockBanded;

  bool IsValid(std::string* error) const;
};

// SPARSE_NORMAL_CHOLESKY on Eigen's sparse LDLT, Levenberg-Marquardt, silent.
ceres::Solver::Options DefaultClipCeresOptions();

// The whole-clip problem's blocks over their own parameter storage, built once and handed
// to either solver (so both minimize the same blocks); SolveClip's first step, exposed for
// tests. Parameter blocks frame by frame: the root translation (3), then the rotation (4)
// of each joint that moves a marker, in joint order (tangent columns in this order: a
// frame's are contiguous, frame_columns of them). Residual blocks: each observed marker
// (robust: takes the loss), then the smoothness terms.
struct ClipProblem {
  struct Parameter {
    double* values;
    int size;
    ceres::Manifold* manifold;  // nullptr: Euclidean.
    bool constant;              // A joint without rotation dofs.
  };
  struct Residual {
    std::unique_ptr<ceres::CostFunction> cost;
    bool robust;
    std::vector<int> blocks;
  };
  std::vector<double> x;  // Per frame: 3 translation + 4 per joint.
  int stride = 0;         // Doubles per frame in x.
  std::vector<Parameter> parameters;
  std::vector<Residual> residuals;
  std::unique_ptr<ceres::LossFunction> loss;
  std::vector<bool> moves;  // Per joint: some marker moves it (it has parameter blocks).
  int frame_columns = 0;    // Tangent columns per frame.

  // The problems own nothing: this ClipProblem must outlive them.
  void AddTo(ceres::Problem* problem) const;  // Options: DO_NOT_TAKE_OWNERSHIP of all.
  void AddTo(DlsProblem* problem) const;
};

Status BuildClipProblem(const Skeleton& skeleton, const MarkerSet& markers,
                        const std::vector<std::vector<Eigen::Vector3d>>& observed,
                        const ClipSolveOptions& options, const Motion& initial, ClipProblem* problem);

struct ClipSolveReport {
  std::string solver;          // ceres | dls.
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int iterations = 0;
  bool usable = false;
  int residual_blocks = 0;
  int parameters = 0;          // Tangent dimension of the problem.
  double rms_marker_error = 0.0;  // Over all observed samples, skeleton units.
  double solve_seconds = 0.0;
  double linear_solve_seconds = 0.0;  // Of which forming and factoring the linear systems.
  std::string brief;
  std::string full;            // Ceres' FullReport() (dls: the brief report).
  double factorization_flops = 0.0;  // dls, block-banded: flops of one factorization.
};

// observed[f][m]: marker m of the marker set at frame f (skeleton units, non-finite =
// missing); motion->frames.size() must equal observed.size().
Status SolveClip(const Skeleton& skeleton, const MarkerSet& markers,
                 const std::vector<std::vector<Eigen::Vector3d>>& observed,
                 const ClipSolveOptions& options, Motion* motion, ClipSolveReport* report);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_CLIP_SOLVER_H_
