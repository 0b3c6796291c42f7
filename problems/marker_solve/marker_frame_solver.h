// MarkerFrameSolver: joint angles of one frame from its observed markers, through the lean
// DLS kernel (kDls: solvers/tree_dls_solver.h, the markers as point rows on the skeleton's
// tree), or, as references on the same residual blocks, through the generic DLS solver
// (kDlsGeneric: solvers/dls_solver.h) or Ceres (kCeres). Both DLS paths run the same
// iterations (solvers/dls_iterations.h): same damping, same stopping rules, same steps to
// round-off.
//
// Unknowns: the root translation (3) and the local rotation of every joint that moves
// some marker (quaternion blocks on RightQuaternionManifold); other joints keep the
// warm-start pose. Residuals: one MarkerResidual per observed marker (missing markers
// are simply absent), optionally robustified (loss), plus an optional pose prior toward
// the previous frame's solution (RotationPriorResidual per joint, TranslationPriorResidual
// for the root), an optional weak rotation prior toward a reference pose (rest_rotations:
// a subject's mean pose, or, when empty, zero local rotations; RotationPriorResidual: with
// a weight well below the previous-frame prior's and the markers', it decides only
// directions no observed marker constrains, e.g. a joint's twist when its only other
// marker is missing, which then relax toward the reference instead of keeping wherever
// the solver's path left them; a hidden joint -- one with markers of its own, none of them
// observed in the frame -- is pulled toward the reference with hidden_rotation_weight
// instead, since only the markers of the bones below it would place it, e.g. a clavicle
// whose one shoulder marker is missing, hinged on by the arm: strong enough to hold it at
// the subject's mean pose; a joint with two or more markers of its own of which exactly one is
// observed is held with twist_rotation_weight about the line from the joint to that marker
// only -- the one direction the marker leaves free, e.g. a foot's turn about its heel marker
// while the toe marker is missing -- and by the rest prior about the others, where the markers
// below observe that twist, after the joints below have made up what they can, by less than
// kTwistObservedFraction of twist_rotation_weight at the warm start
// (problems/marker_solve/twist_observability.h: a humerus whose forearm hinges on it is left to
// the forearm), and
// soft joint limits (JointLimitResidual) where the skeleton has them.
// Each joint's rotation stays on its dof set (Skeleton::rotation_axes, RotationManifold).
//
// Units: observations in the skeleton's length units; marker residuals scaled by
// marker_weight; the prior's rotation weight is per radian, its translation weight per
// skeleton unit. Costs are 1/2 sum of squared (robustified) residuals, as Ceres reports.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_FRAME_SOLVER_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_FRAME_SOLVER_H_

#include <memory>
#include <string>
#include <vector>

#include <ceres/loss_function.h>
#include <ceres/solver.h>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "solvers/dls_solver.h"
#include "solvers/solver_kind.h"

namespace mocapsolve {

// A joint's twist about its one observed marker is held (twist_rotation_weight) only where the
// markers below observe it by less than this fraction of the prior's weight: observed at all
// (a forearm hinged on a humerus, 60 mm/rad against the prior's 100) it is better placed by
// them than by the mean pose (BENCHMARKS.md: a gate at the full weight moved LUPA 3.9 -> 28 mm).
inline constexpr double kTwistObservedFraction = 0.1;

struct MarkerSolveOptions {
  SolverKind solver = SolverKind::kDls;  // As every command's --solver.
  double marker_weight = 1.0;
  std::string loss = "none";     // none | huber | cauchy
  double loss_scale = 1.0;       // Skeleton units (the residual size where the loss bends).
  double prior_rotation_weight = 0.0;     // Per radian, toward the previous solution.
  double prior_translation_weight = 0.0;  // Per skeleton unit.
  double rest_rotation_weight = 0.0;      // Per radian, toward rest_rotations; 0 = off.
  // The rest prior's reference, one local rotation per joint (a subject's mean pose);
  // empty: zero rotations. Another size is an error at Solve.
  QuaternionVector rest_rotations;
  // Per radian, toward rest_rotations, of a joint with markers of its own none of which is
  // observed in the frame (replaces rest_rotation_weight on that joint then); 0 = off.
  // Only toward a given reference (non-empty rest_rotations).
  double hidden_rotation_weight = 0.0;
  // Per radian, toward rest_rotations, of the twist of a joint with two or more markers of
  // its own exactly one of which is observed, about the line from the joint to that marker
  // (the rest prior's weight stays on the other directions), where the markers below observe
  // that twist by less than kTwistObservedFraction of this weight (TwistObservability at the
  // warm start, over the observed markers, times marker_weight; a marker at the joint's
  // origin: never). 0 = off. Only toward a given reference.
  double twist_rotation_weight = 0.0;
  // The rest prior applies only toward a given reference (empty rest_rotations: off): the
  // default weight is meant for a subject's mean pose, not for zero rotations.
  bool rest_prior_needs_reference = false;
  double limit_weight = 0.0;     // Per radian outside a joint's limits (ASF); 0 = off.
  ceres::Solver::Options ceres;  // Used when solver == kCeres.
  DlsOptions dls;                // Used when solver == kDls or kDlsGeneric.

  bool IsValid(std::string* error) const;
};

// Ceres options that suit small dense per-frame problems.
ceres::Solver::Options DefaultFrameCeresOptions();

struct FrameSolveReport {
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int iterations = 0;
  bool usable = false;         // The solver returned a usable solution.
  int markers_used = 0;
  double rms_marker_error = 0.0;  // sqrt(mean |x_pred - x_obs|^2), skeleton units.
  // Hidden joints held toward the reference with hidden_rotation_weight in this frame.
  std::vector<int> held_joints;
  // Joints held about the line to their one observed marker with twist_rotation_weight.
  std::vector<int> twist_held_joints;
  std::string brief;           // The solver's one-line report.
};

// The ceres::LossFunction for options.loss (nullptr for "none"); error on an unknown name.
Status MakeLoss(const std::string& name, double scale, std::unique_ptr<ceres::LossFunction>* loss);

class MarkerFrameSolver {
 public:
  // Keeps references to the skeleton and marker set: they must outlive the solver.
  MarkerFrameSolver(const Skeleton& skeleton, const MarkerSet& markers,
                    const MarkerSolveOptions& options);
  ~MarkerFrameSolver();

  // observed[m] for marker m of the marker set, skeleton units; a non-finite entry means
  // missing. `pose` is the warm start on input and the solution on output; with a prior,
  // the input pose is also the prior's reference.
  Status Solve(const std::vector<Eigen::Vector3d>& observed, Pose* pose, FrameSolveReport* report);

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// RMS over markers of |x_pred - x_obs| at a pose (skeleton units), skipping missing ones.
double RmsMarkerError(const Skeleton& skeleton, const MarkerSet& markers, const Pose& pose,
                      const std::vector<Eigen::Vector3d>& observed, int* count = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_FRAME_SOLVER_H_
