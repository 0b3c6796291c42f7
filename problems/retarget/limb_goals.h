// Limb goals: what the limb direction term of the per-frame retarget solve
// (LimbDirectionResidual, retarget_frame_solver.h) asks of each limb.
//
// The limbs are those the quality measure compares (retarget_quality.h, MappedLimbs):
// upper arms, forearms, thighs and shins, the target's role joint a toward the next role's
// joint b, and the source joints mapped to them. Per limb, u = the rest direction a -> b in
// a's frame (LimbDirectionInJoint at the target's rest pose). Per frame f, the goal
//   d(l, f) = T (p_s1(f) - p_s0(f)) / |p_s1(f) - p_s0(f)|,   T = F_t^T F_s
// the source limb's world direction (its motion as retargeted, up axis turned) turned by the
// rotation the vertex goals use (retarget_setup.h: the characters' facings), so the goals
// live in the target's world as the vertex goals do. A zero-length source limb gives a zero
// goal (no pull). Directions only: the target keeps its own limb lengths.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_LIMB_GOALS_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_LIMB_GOALS_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "problems/retarget/joint_map.h"
#include "problems/retarget/retarget_frame_solver.h"
#include "problems/retarget/retarget_setup.h"

namespace mocapsolve {

struct LimbGoals {
  std::vector<RetargetSolveOptions::Limb> limbs;  // Target joint a and u.
  std::vector<std::string> names;                 // "left_upper_arm", ...
  std::vector<Eigen::Matrix3Xd> directions;       // Per frame, 3 x #limbs.
};

// Limbs with a zero rest length on the target are left out.
LimbGoals ComputeLimbGoals(const JointMap& map, const Skeleton& source, const Motion& source_motion,
                           const Skeleton& target, const Pose& target_rest, const RetargetSetup& setup);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_LIMB_GOALS_H_
