// JointMap: which source joint corresponds to which target joint, for retargeting a
// skeleton-only motion (retarget_character.h) and for the foot plants.
//
// Automatic, by names, in two passes over the joints (each joint is mapped at most once):
//   1. equal normalized names; normalized = lower case, everything up to the last ':' or
//      '|' dropped (Mixamo's "mixamorig:"), and only letters and digits kept
//      ("Shoulder.L" -> "shoulderl");
//   2. equal canonical names: a synonyms table brings the usual conventions to Mixamo's
//      names (without prefix):
//        CMU ASF  root lowerback upperback thorax lowerneck upperneck head, and per side
//                 lclavicle lhumerus lradius lwrist lfemur ltibia lfoot ltoes
//                 (lwrist is at the wrist, so it is the Mixamo LeftHand; lhand, lfingers
//                 and lthumb are left unmapped: the mesh's fingers follow the wrist);
//        CMU BVH  Hips LowerBack Spine Spine1 Neck Neck1 Head, LeftShoulder LeftArm
//                 LeftForeArm LeftHand LeftUpLeg LeftLeg LeftFoot LeftToeBase (Mixamo's
//                 own names, so pass 1 maps them);
//        Blender-style  Hips Abdomen Torso Neck Head, Shoulder.L UpperArm.L LowerArm.L
//                 Hand.L UpperLeg.L LowerLeg.L Foot.L Toe.L (RobotExpressive), and
//                 Thigh/Shin/Calf/Clavicle/UpperArm/LowerArm with Left/Right/L/R/.L/_L.
//   Joints of other conventions (CesiumMan's leg_joint_L_1) map only by equal names
//   or through overrides; there is no topological fallback (see the README).
// Overrides: (source name, target name) pairs, applied after the automatic passes; each
// replaces whatever either joint was mapped to. A name that is not a joint of its
// skeleton is an error naming it.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_JOINT_MAP_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_JOINT_MAP_H_

#include <string>
#include <utility>
#include <vector>

#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct JointMap {
  std::vector<int> target_of_source;  // #Js, -1 where unmapped.
  std::vector<int> source_of_target;  // #Jt, -1 where unmapped.
  int num_mapped() const;
};

// Lower case, prefix up to the last ':' or '|' dropped, letters and digits only.
std::string NormalizeJointName(const std::string& name);
// The Mixamo-style canonical name of a normalized name ("lfemur" -> "leftupleg"), or the
// normalized name itself when the table has no entry.
std::string CanonicalJointName(const std::string& normalized);

// Errors: an override naming a joint that does not exist (which side and which name).
Status BuildJointMap(const Skeleton& source, const Skeleton& target,
                     const std::vector<std::pair<std::string, std::string>>& overrides,
                     JointMap* map);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_JOINT_MAP_H_
