// A source whose skeleton is the target's own (a character's clip written as BVH and
// retargeted back onto the character must come back as itself).
//
// Same skeleton (IsSameSkeleton): the joint map (joint_map.h) is one-to-one and complete
// (every joint of either side mapped), it keeps the hierarchy (the target joint of a source
// joint's parent is the parent of its target joint), and the rest offsets agree up to one
// scale k (the target's units per source unit):
//     k = sum_j <o_s(j), o_t(m(j))> / sum_j |o_s(j)|^2        (least squares, non-root j)
//     |k o_s(j) - o_t(m(j))| <= kSameSkeletonTolerance * max_j |o_t(j)|   for every j,
// offsets in their parent's frame. The tolerance (1e-4 of the longest bone) is far above
// the rounding of a text file (a BVH keeps 6 significant digits: 5e-6 of a value) and far
// below any difference between two characters' skeletons.
// Offsets in the parent's frame agreeing means the local frames agree after each joint's
// rest rotation: world_from_joint has the same rotation on both sides when
//     R_rest_t(m(j)) R_t(m(j)) = R_rest_s(j) R_s(j).
//
// The transfer (TransferOwnMotion) is then exact, joint by joint, with no surface in
// between: per frame and target joint t = m(j),
//     R_t = R_rest_t^-1 R_rest_s R_s,
//     translation_t = k translation_s   (the target's own offset where the source's
//                                        translation is its offset, exactly),
// the root's world included (so the source motion is expected in the target's world:
// Y up, as RetargetMotionOntoCharacter turns it). Joint world positions are k times the
// source's; rotations are equal.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_OWN_SKELETON_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_OWN_SKELETON_H_

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "problems/retarget/joint_map.h"

namespace mocapsolve {

constexpr double kSameSkeletonTolerance = 1e-4;

// True (and *scale = k) if `source` is `target`'s skeleton under `map` (see the header).
bool IsSameSkeleton(const Skeleton& source, const Skeleton& target, const JointMap& map, double* scale);

// The source motion on the target skeleton (IsSameSkeleton must hold for map and scale).
Motion TransferOwnMotion(const Skeleton& source, const Motion& source_motion, const Skeleton& target,
                         const JointMap& map, double scale);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_OWN_SKELETON_H_
