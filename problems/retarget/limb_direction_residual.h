// LimbDirectionResidual: asks one limb of the target (upper arm, forearm, thigh or shin,
// from its role joint a toward the next role's joint) to point as the source's limb does,
// an extra block of the per-frame retarget solve (retarget_frame_solver.h).
//
//   r = scale * (R_a(q) u - d)                                        3 rows, unitless
//
// with R_a the world rotation of target joint a from the chain's forward kinematics
// (kinematics/chain_kinematics.h), u the limb's unit direction in a's frame (its rest
// direction from a to the next role's joint: the bone offset when that joint is a's child;
// intermediate joints such as twist bones are taken at their rest rotation), d the goal
// direction (unit, target world: the source's limb direction turned into the target's
// world, retarget_character.h) and scale = limb_direction_weight. |R_a u - d| is
// 2 sin(angle / 2), so a weight w costs about w^2 angle^2 / 2 for small angles: w per
// radian, on the scale of a normal-tracked vertex (1 per unit of normal difference).
//
// Parameter blocks, in order (as TrackedVertexResidual's, so one Problem holds both):
//   0:      the root translation t_root, 3 doubles (no effect: its Jacobian is zero);
//   1 + s:  the local rotation q_j of joint j = chain(a)[s] (the ancestors of a and a
//           itself, parents first, starting at the root), 4 doubles (x, y, z, w) on
//           RightQuaternionManifold (R_j <- R_j exp(delta)).
//
// Jacobians (row-major; any may be null):
//   d r / d t_root = 0 (3 x 3);
//   d r / d q_j    = -scale [R_a u]x R_j * AmbientFromTangent(q_j) / |q_j|   (3 x 4).
// This is the normal row of TrackedVertexResidual for a vertex of weight 1 on joint a
// whose rest normal is u, which is how the lean DLS kernel stacks it (a direction row).
// The goal is read through a pointer at each Evaluate (one Problem for the whole clip).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_LIMB_DIRECTION_RESIDUAL_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_LIMB_DIRECTION_RESIDUAL_H_

#include <vector>

#include <ceres/cost_function.h>
#include <Eigen/Core>

#include "kinematics/chain_kinematics.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

// u: the unit direction from joint `from` to joint `to` in from's frame at `pose`
// (normally the rest pose); zero when the two coincide.
Eigen::Vector3d LimbDirectionInJoint(const Skeleton& skeleton, const Pose& pose, int from, int to);

class LimbDirectionResidual : public ceres::CostFunction {
 public:
  // The skeleton and goal must outlive the residual; `local` is u (unit).
  LimbDirectionResidual(const Skeleton* skeleton, int joint, const Eigen::Vector3d& local,
                        const Eigen::Vector3d* goal, double scale);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  const std::vector<int>& joints() const { return chain_.joints; }
  int joint() const { return joint_; }
  const Eigen::Vector3d& local() const { return local_; }
  double scale() const { return scale_; }

 private:
  const Skeleton* skeleton_;
  int joint_;
  Eigen::Vector3d local_;
  const Eigen::Vector3d* goal_;
  double scale_;
  JointChain chain_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_LIMB_DIRECTION_RESIDUAL_H_
