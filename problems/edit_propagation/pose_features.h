// Pose features: the pose vectors p_i of the "magic wand" paper (Dean, Lewis and Chalmers
// 2018, section 3: "concatenated rotational degrees of freedom ... log quaternions").
//
// Row i of the #frames x D matrix is, for each selected joint j (in skeleton order),
//
//   weight_j * log(q_j(i))          (3 values, radians; the rotation vector angle * axis)
//
// where each joint's quaternion series is first made sign-continuous over the clip (so
// the log map does not jump between q and -q), followed, when temporal_weight > 0, by one
// column temporal_weight * t_i (t_i = i / frame_rate, seconds; so temporal_weight is in
// radians per second): section 3.1's option of adding temporal distance to d(p_i, p_j).
// Joint translations (root position) are not features.
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_POSE_FEATURES_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_POSE_FEATURES_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct PoseFeatureOptions {
  std::vector<std::string> joints;    // Joint names; empty = every joint with rotation dofs.
  std::vector<double> joint_weights;  // One per selected joint (>= 0); empty = 1 each.
  double temporal_weight = 0.0;       // Radians per second of clip time; 0 = none.
};

// Fails (message names the field) on an unknown joint, a weight count that does not match,
// a negative or non-finite weight, an empty motion or a motion that does not fit the skeleton.
Status PoseFeatures(const Skeleton& skeleton, const Motion& motion,
                    const PoseFeatureOptions& options, Eigen::MatrixXd* features);

// Median over i of |p_{i+1} - p_i| (0 for fewer than 2 rows): the scale of the auto sigma.
double MedianStepDistance(const Eigen::MatrixXd& features);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_POSE_FEATURES_H_
