// A subject's mean pose: each joint's mean local rotation over a motion, the chordal L2
// mean argmin_r sum_f |q_f - s_f r|^2 over unit quaternions r: the quaternions
// sign-aligned with frame 0's (s_f = sign(q_f . q_0)), summed and normalized. The sum is
// never zero (each aligned term has a non-negative dot product with q_0, which has 1).
// Used for a lone joint's gauge (lone_joint_gauge.h) and as the rest prior's reference of a
// fitted or calibrated subject (pipeline/subject.h "mean_pose", MarkerSolveOptions::rest_rotations).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MEAN_POSE_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MEAN_POSE_H_

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

// Joint j's mean local rotation over the motion (identity for an empty motion).
Eigen::Quaterniond MeanLocalRotation(const Motion& motion, int joint);

// MeanLocalRotation of every joint of the skeleton, in joint order.
QuaternionVector MeanPose(const Skeleton& skeleton, const Motion& motion);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MEAN_POSE_H_
