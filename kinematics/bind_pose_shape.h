// What a character's bind pose looks like: its height and whether its arms are out
// (T-pose), down at an angle (A-pose) or otherwise, for `mocapsolve info`.
//
// Arms: for an up axis (the file's first, then the other two until one fits), the two
// joints farthest out to either side along the wider horizontal axis are taken as the
// hands (or finger tips); their lowest common ancestor is the chest, which must lie
// above or below the root along that axis (the body's up: its sign gives up_sign, so a
// Z-up file is read as Z-up). The two are an arm pair when their chains from the chest
// (continued below the outermost joints through each one's largest subtree, so an arm
// hanging down counts whole) have the same number of joints and lengths within 20 %, and their heights differ by at
// most 15 % of the height. On each chain (chest exclusive, hand inclusive) the upper arm is the
// bone that starts at the first joint named like one (…UpperArm…, …humerus…, …Arm but not
// …ForeArm/…LowerArm), else the second bone of a chain of four or more joints (the first
// is the clavicle), else the first; zero-length bones are skipped.
// Kind: the upper arms' angle below the horizontal plane, e = asin(-d . up) for the unit
// bone direction d: T-pose when |e| <= 15 deg on both sides, A-pose when 15 < e <= 65 deg
// on both, else other (and other when no arm pair is found: a quadruped, one arm).
#ifndef MOCAPSOLVE_KINEMATICS_BIND_POSE_SHAPE_H_
#define MOCAPSOLVE_KINEMATICS_BIND_POSE_SHAPE_H_

#include <string>

#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

struct BindPoseShape {
  int up_axis = 1;             // 0 x, 1 y, 2 z (the body's, or the file's when no arms).
  int up_sign = 1;             // +1 or -1.
  double height = 0.0;         // Extent along the up axis, skeleton units.
  bool height_from_mesh = false;  // Else from the joints (and end sites).
  std::string kind = "other";  // "T-pose", "A-pose" or "other".
  std::string reason;          // Why "other" when no arm pair was found; else "".
  // The two upper arms found ("LeftArm -> LeftForeArm"; the one on the -lateral side
  // first) and their angle below horizontal (degrees; negative: raised). Empty when no
  // arm pair was found.
  std::string upper_arms[2];
  double below_horizontal_deg[2] = {0.0, 0.0};
};

// `pose` is the bind (or rest) pose; `vertices` (3 x #V, the mesh in that pose, may be
// empty) gives the height when present. file_up_axis: the format's convention (glTF, BVH,
// ASF: 1 = Y).
BindPoseShape DescribeBindPose(const Skeleton& skeleton, const Pose& pose, const Eigen::Matrix3Xd& vertices,
                               int file_up_axis = 1);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_BIND_POSE_SHAPE_H_
