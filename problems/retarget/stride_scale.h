// Stride length across proportions: a skeleton-only source's horizontal root motion scaled
// so that the target's steps are as long, relative to its legs, as the source's.
//
// The retarget maps the source into the target's scale by the height ratio k
// (skeleton_binding.h), so the hips travel k times the source's distance. A character
// whose legs are a different share of its height (a stylized robot with a big head and
// short legs) then has to cover a step its legs cannot reach, and the foot plants
// (foot_plant_residual.h) lose to the vertex goals: planted feet slide. With L the leg
// length (thigh joint to foot joint along the bones, mean of both sides; the joint map's
// thigh and foot roles on each side),
// the stride factor is
//     s = (L_t / L_s) / k,
// and the source root's horizontal translation about its first frame is multiplied by s
// before the solve:  t_root(f).xz <- t_root(0).xz + s (t_root(f).xz - t_root(0).xz)
// (world Y up, as RotateMotionWorld leaves the source). Vertical motion is kept.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_STRIDE_SCALE_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_STRIDE_SCALE_H_

#include <utility>
#include <vector>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

// Thigh joint to foot joint along the bones (sum of the rest offsets' lengths; a foot that
// is not below its thigh, such as an IK bone parented to a root bone, the distance in the
// rest pose), mean over the (thigh, foot) pairs with both joints (>= 0); 0 when none has.
double LegLength(const Skeleton& skeleton, const std::vector<std::pair<int, int>>& thigh_foot);

// Multiplies the root's horizontal translation about frame 0 by `factor`.
void ScaleRootStride(double factor, Motion* motion);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_STRIDE_SCALE_H_
