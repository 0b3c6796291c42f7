// The gauge of a joint that one marker alone constrains. A marker x = p_j + R_parent
// Q_j q_j z (Q_j the joint's rest rotation, q_j its local rotation, z the offset) on a
// joint j that no other marker rides on, nor any marker on a joint below it, fixes only
// the product q_j z: (q_j r^-1, r z) fits the markers as well for any rotation r. A fit
// leaves r wherever its iterations took it, so when the marker is missing (occluded, or
// left out by leave_one_out.h) the solve keeps j at its warm start (the rest pose,
// q_j = 1) and predicts p_j + R_parent Q_j z: off by |q_j z - z|, a constant 15-20 cm
// on the toes of a fitted 53-marker take. FixLoneJointGauges picks r = the mean of the
// fitted q_j over the motion (the chordal L2 mean, mean_pose.h), so the rest pose is the joint's mean pose, and on a 3-dof joint turns it
// the least so that r z points along mean_f q_j z (one marker leaves the twist about z
// free, so the mean rotation can miss the mean position): z' = r z and every frame's
// q_j' = q_j r^-1 (the markers' world positions do not change). Joints with 1 or 3
// rotation dofs only: q_j r^-1 stays on a single axis, and any rotation is on the full
// set; a 2-dof joint's product would leave its dof set.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LONE_JOINT_GAUGE_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LONE_JOINT_GAUGE_H_

#include <string>
#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

// Rewrites *markers (offsets) and *motion (local rotations) as above for every lone
// joint; `labels` gets the labels of the markers whose offsets changed. Errors: a motion
// of another skeleton size, an empty motion.
Status FixLoneJointGauges(const Skeleton& skeleton, MarkerSet* markers, Motion* motion,
                          std::vector<std::string>* labels);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LONE_JOINT_GAUGE_H_
