// RetargetFrameSolver: the target pose of one frame from the tracked vertices' goals
// (thesis Algorithm 6, eqs. 14-18), through a lean DLS kernel, through the generic
// DLS solver (solvers/dls_solver.h) or through Ceres, all on the same residuals.
//
// Unknowns: the target root translation (3) and the local rotation of every joint on
// some tracked vertex's chain (quaternions, increments R_j <- R_j exp(delta_j), delta in
// the joint's local frame; every joint is treated as a free 3-dof rotation, as glTF
// joints are). Other joints keep the warm-start pose.
//
// Residuals, stacked (eq. 17 with the blend mask B of retarget_setup.h):
//   per tracked vertex s: TrackedVertexResidual (tracked_vertex_residual.h), 3 rows,
//     position ones scaled by position_weight / sigma, normal ones by normal_weight;
//   optional temporal smoothness toward the previous frame's solution (the warm start):
//     RotationPriorResidual per solved joint (smoothness_weight per radian) and
//     TranslationPriorResidual for the root (smoothness_weight / sigma per unit);
//   optional foot plants: FootPlantResidual per options.plant_joints entry, 3 rows,
//     scale plant_weight / sigma while planted (SetPlants), 0 otherwise (the rows stay,
//     so the problem's shape does not change from frame to frame);
//   optional soft joint limits (JointLimitResidual, limit_weight per radian) where the
//     target skeleton has limits (problems/marker_solve/, reused as they are);
//   optional limb directions: LimbDirectionResidual (limb_direction_residual.h) per
//     options.limbs entry, 3 rows, scale limb_direction_weight, toward the goal direction
//     of the frame (SetLimbGoals; a zero goal gives the row no gradient). Only when
//     limb_direction_weight > 0;
//   optional floor: per options.floor_joints entry k, joint k kept at or above its lowest
//     height h_k (options.floor_heights: the floor plus the joint's rest clearance,
//     foot_clearance.h), weight floor_weight / sigma. Ceres and the generic DLS take
//     FloorResidual (floor_residual.h, one-sided, one row); the lean kernel, whose rows are
//     3-row points, an active set: after the frame's solve each joint under its h_k gets a
//     point row toward (x_k, h_k, z_k) of that solution and the frame is solved once more
//     (from it), the rows then off again. Only when floor_weight > 0.
//
// DLS (kDls, kDlsGeneric): a fixed number of iterations, every step taken (Buss), with
//   delta = J^T (J J^T + lambda I)^-1 e   (eq. 18)   =   (J^T J + lambda I)^-1 J^T e,
// e = -r, J the tangent Jacobian (3 #tracked (+ prior rows) by 3 + 3 #solved joints).
// The root translation's tangent is in units of sigma (t <- t + sigma delta_t, for every
// solver), so that its columns are on the scale of the normalized rotation columns and
// the fixed lambda damps both alike (thesis 4.3.3 divides GP_t by sigma).
// kDls is the lean tree kernel (solvers/tree_dls_solver.h): each tracked vertex a point or
// direction row blended over its influences, each plant a point row on the foot joint,
// priors and limits as block costs; FK once per iteration, J^T J assembled from moments
// summed up the tree and factored leaves first (J is never formed). kDlsGeneric is
// DlsSolver on the residual blocks; both run solvers/dls_iterations.h, so the test checks
// them step for step.
// Ceres (kCeres): the blocks in a ceres::Problem, Levenberg-Marquardt,
// max_num_iterations = iterations.
//
// Costs are 1/2 |r|^2 over the tracked-vertex rows (and priors/limits when on).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_FRAME_SOLVER_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_FRAME_SOLVER_H_

#include <memory>
#include <string>
#include <vector>

#include <ceres/solver.h>
#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"
#include "problems/retarget/retarget_setup.h"
#include "solvers/solver_kind.h"

namespace mocapsolve {

struct RetargetSolveOptions {
  SolverKind solver = SolverKind::kDls;
  int iterations = 10;           // Per frame (thesis: 10; Table 4: 5).
  double lambda = 5.0;           // DLS damping (eq. 18).
  double position_weight = 1.0;  // Per sigma of position error.
  double normal_weight = 1.0;    // Per unit of normal difference.
  double smoothness_weight = 0.0;  // Per radian toward the previous frame; 0 = off.
  double limit_weight = 0.0;       // Per radian outside joint limits; 0 = off.
  bool time_stages = false;        // Accumulate RetargetStageTimes (kDls only).
  // Foot plants (FootPlantResidual, foot_plant_residual.h): target joints that may be held
  // at an anchor (SetPlants), each weighted plant_weight / sigma while planted.
  std::vector<int> plant_joints;
  double plant_weight = 30.0;
  // Limb directions (LimbDirectionResidual): target joint a and the limb's unit direction
  // in a's frame (LimbDirectionInJoint), each asked to point along its goal (SetLimbGoals)
  // with weight limb_direction_weight (per unit of direction difference, ~ per radian);
  // no rows when the weight is 0.
  struct Limb {
    int joint = -1;
    Eigen::Vector3d local = Eigen::Vector3d::UnitY();
  };
  std::vector<Limb> limbs;
  double limb_direction_weight = 0.0;
  // The floor (FloorResidual): target joints kept at or above a height (target world y,
  // one per joint), weight floor_weight per sigma of depth; no rows when it is 0.
  std::vector<int> floor_joints;
  std::vector<double> floor_heights;
  double floor_weight = 0.0;
  ceres::Solver::Options ceres;    // kCeres; max_num_iterations is set from iterations.

  bool IsValid(std::string* error) const;
};

// Ceres options for these small dense problems: Levenberg-Marquardt, DENSE_NORMAL_CHOLESKY,
// single thread, Ceres' default initial trust region (1e4; a radius of ~1 helps the
// cross-character glTF cases, see the retarget command's --ceres_trust_radius).
ceres::Solver::Options DefaultRetargetCeresOptions();

// Seconds spent in each stage of the lean DLS iterations (thesis Table 3), from the tree
// kernel's TreeDlsStageTimes: FK; "skinning": the tracked vertices' points, residuals and
// row moments (and the prior/limit rows); "jacobian": the moments expanded into the blocks
// of J^T J and J^T r; "solve": damping, factorization and solve; "update": the retraction.
struct RetargetStageTimes {
  double fk = 0.0, skinning = 0.0, jacobian = 0.0, solve = 0.0, update = 0.0;
  int iterations = 0;
  double total() const { return fk + skinning + jacobian + solve + update; }
};

struct RetargetFrameReport {
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int iterations = 0;
  int floor_contacts = 0;  // Floor joints under their lowest height after the first solve.
  double mean_position_error = 0.0;  // Mean |v - g| over all tracked vertices, target units.
  double mean_normal_angle = 0.0;    // Mean angle between n and m (radians), all tracked.
  double mean_effector_error = 0.0;  // Mean |v - g| over the position-tracked ones (hands, feet,
                                     // head: the end effectors), target units; 0 if none.
};

class RetargetFrameSolver {
 public:
  // Keeps references to everything: it must outlive the solver. sigma from
  // RetargetGoals. Options must be valid (CHECKed).
  RetargetFrameSolver(const Skeleton& skeleton, const SkinnedMesh& mesh, const RetargetSetup& setup,
                      double sigma, const RetargetSolveOptions& options);
  ~RetargetFrameSolver();

  // Goals 3 x #tracked. `pose` is the warm start (and the smoothness reference) on input,
  // the solution on output. `report` may be null (then the errors are not computed).
  Status Solve(const Eigen::Matrix3Xd& goal_positions, const Eigen::Matrix3Xd& goal_normals,
               Pose* pose, RetargetFrameReport* report);

  // Anchors (3 x #plant_joints, target units) and which plants are on for the next Solve
  // calls (default: all off).
  void SetPlants(const Eigen::Matrix3Xd& anchors, const std::vector<char>& active);

  // Goal directions of the limbs for the next Solve calls (3 x #options.limbs, unit, target
  // world; a zero column: no pull). Ignored when the limb term is off. Default: zero.
  void SetLimbGoals(const Eigen::Matrix3Xd& directions);

  const RetargetStageTimes& stage_times() const;
  void ResetStageTimes();

  // The lean kernel's residual (3 #tracked, then 3 per plant joint, then 3 per limb when
  // the limb term is on, then 3 per floor joint when the floor is on: zero, its active-set
  // rows being off outside Solve) and tangent Jacobian in
  // the pose tangent layout of kinematic_jacobians.h (3 + 3 #J columns; unsolved joints'
  // columns zero), at `pose` with the given goals (TreeDlsSolver::Linearize). For tests.
  void Linearize(const Eigen::Matrix3Xd& goal_positions, const Eigen::Matrix3Xd& goal_normals,
                 const Pose& pose, Eigen::VectorXd* residual, Eigen::MatrixXd* jacobian);

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// Mean |v - g| (target units) and mean normal angle (radians) of the tracked vertices at a
// pose, all of them whatever their mask; optionally the mean |v - g| of the position-tracked
// ones only (the end effectors; 0 when there are none).
void TrackedVertexErrors(const Skeleton& skeleton, const SkinnedMesh& mesh,
                         const RetargetSetup& setup, const Pose& pose,
                         const Eigen::Matrix3Xd& goal_positions, const Eigen::Matrix3Xd& goal_normals,
                         double* mean_position_error, double* mean_normal_angle,
                         double* mean_effector_error = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_FRAME_SOLVER_H_
