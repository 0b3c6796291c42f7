// A motion moved onto another description of the same skeleton.
#ifndef MOCAPSOLVE_KINEMATICS_MOTION_ON_SKELETON_H_
#define MOCAPSOLVE_KINEMATICS_MOTION_ON_SKELETON_H_

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

// The motion of `from` re-expressed on `to`, the same skeleton (joint names and parents in
// the same order, the same offsets) but with other rest rotations, e.g. the subject's ASF
// skeleton for a BVH written from it (a BVH has no rest rotations: the writer folds them
// into the rotations, io/bvh_writer.h). Per joint R_to = R_rest_to^-1 * R_rest_from * R_from,
// so forward kinematics is unchanged. Lengths: when both units are known they are
// converted (translations scaled); an unknown unit is taken to be the other's. Offsets
// must agree to 1e-5 of the skeleton's largest offset (a BVH's printed digits), else the
// error names the first joint that differs (a motion of another skeleton). `out` may be
// `&motion`.
Status MotionOnSkeleton(const Skeleton& from, const Motion& motion, const Skeleton& to, Motion* out);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_MOTION_ON_SKELETON_H_
