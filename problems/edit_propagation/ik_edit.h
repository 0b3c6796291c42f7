// IK edits: "move joint X to position P at frame i", solved with the marker-solving
// machinery (problems/marker_solve/marker_frame_solver.h) and turned into a PoseEdit.
//
// Each target joint is a marker at zero offset on that joint, observed at P (world frame,
// skeleton units). MarkerFrameSolver minimizes
//
//   sum_targets |marker_weight (x_X(q, t_root) - P)|^2
//     + sum_j |2 prior_rotation_weight (q_j - s q_j^orig)|^2 + |prior_translation_weight (t_root - t_root^orig)|^2
//
// over the root translation and the rotations of the joints on the targets' chains,
// starting from and pulled toward the original pose of frame i (the prior keeps the rest
// of the pose in place and picks, among the many poses that reach P, one near the
// original). Ceres or the DLS solver (options.solver) minimize the same residual blocks.
// Weights as in MarkerSolveOptions: the prior's rotation weight is in skeleton units of
// target error per radian, its translation weight per skeleton unit.
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_IK_EDIT_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_IK_EDIT_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/edit_propagation/pose_edit.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

struct IkTarget {
  int joint = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // World, skeleton units.
};

struct IkEditReport {
  FrameSolveReport solve;
  double max_target_error = 0.0;  // max |x_X - P| at the solution, skeleton units.
};

// Errors: frame or joint out of range, non-finite targets, a failed solve.
Status SolveIkEdit(const Skeleton& skeleton, const Motion& motion, int frame,
                   const std::vector<IkTarget>& targets, const MarkerSolveOptions& options,
                   PoseEdit* edit, IkEditReport* report);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_IK_EDIT_H_
