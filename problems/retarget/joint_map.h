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
//   3. structure (humanoid_roles.h), when both skeletons are humanoids and names did not
//      make the source the target's own skeleton (own_skeleton.h): a name link whose
//      joints play different roles (or different role groups: the spine chain is one) is
//      dropped, and every role found on both sides links its two joints where names left
//      it unmapped or disagree (spine_i with spine_i while both are unmapped). A remaining
//      name link is dropped when the nearest role joints above its two joints are not
//      linked to each other (a left finger named like a right one).
//      When neither is a humanoid and both have the same hierarchy (parents array), the
//      joints left unmapped on both sides map by index ("topology": a Fox onto a Fox).
// Overrides: (source name, target name) pairs, applied after the automatic passes; each
// replaces whatever either joint was mapped to. A name that is not a joint of its
// skeleton is an error naming it and the side.
// Every link records how it was decided (name, structure, topology, file); `roles` lists
// each role of either side with its two joints, and
//   confidence = (roles linked on both sides / roles found on either side)
//                * min(side certainty of the two skeletons)          (both humanoids),
//              = mapped joints / max(#Js, #Jt)                        (otherwise).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_JOINT_MAP_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_JOINT_MAP_H_

#include <string>
#include <utility>
#include <vector>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"
#include "problems/retarget/humanoid_roles.h"

namespace mocapsolve {

struct JointMapRole {
  std::string role;
  int source = -1, target = -1;  // -1: not on that side (or not linked).
  std::string how;               // How source is linked: name|structure|topology|file; "" unlinked.
};

struct JointMap {
  std::vector<int> target_of_source;  // #Js, -1 where unmapped.
  std::vector<int> source_of_target;  // #Jt, -1 where unmapped.
  std::vector<std::string> how_of_source;  // #Js: name|structure|topology|file, "" unmapped.
  HumanoidRoles source_roles, target_roles;
  std::vector<JointMapRole> roles;
  double confidence = 0.0;
  int num_mapped() const;
  // "humanoid (roles: pelvis, ...)" or "not a humanoid (<why>)", for the source or target.
  std::string Found(bool source) const;
};

// A skeleton as the map sees it: standing (rest or bind pose world positions) and, if known,
// which joints carry vertex weight.
// Where the sides cannot be told from geometry in `positions` (arms and legs straight),
// `other_positions` (a second pose, e.g. a glTF's node rest pose beside its bind pose) is
// tried.
struct JointMapSkeleton {
  const Skeleton* skeleton = nullptr;
  Vector3dVector positions;
  Vector3dVector other_positions;  // Empty: none.
  std::vector<bool> weighted;
};
// pose empty = RestPose; other empty = none; mesh nullptr = weights unknown.
JointMapSkeleton StandingSkeleton(const Skeleton& skeleton, const Pose& pose, const SkinnedMesh* mesh,
                                  const Pose& other = Pose());
// FindHumanoidRoles on `positions`, or on other_positions where only they tell the sides.
HumanoidRoles FindRoles(const JointMapSkeleton& skeleton);

// Lower case, prefix up to the last ':' or '|' dropped, letters and digits only.
std::string NormalizeJointName(const std::string& name);
// The Mixamo-style canonical name of a normalized name ("lfemur" -> "leftupleg"), or the
// normalized name itself when the table has no entry.
std::string CanonicalJointName(const std::string& normalized);

// Errors: an override naming a joint that does not exist (which side and which name).
Status BuildJointMap(const JointMapSkeleton& source, const JointMapSkeleton& target,
                     const std::vector<std::pair<std::string, std::string>>& overrides,
                     JointMap* map);
// One line: "joint map: N joints (a by name, b by structure, ...); source humanoid (sides
// from geometry), target ...; confidence c".
std::string JointMapNote(const JointMap& map);

// The same with both skeletons in their rest poses and unknown weights.
Status BuildJointMap(const Skeleton& source, const Skeleton& target,
                     const std::vector<std::pair<std::string, std::string>>& overrides,
                     JointMap* map);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_JOINT_MAP_H_
