// FindHumanoidRoles: which joint of a skeleton plays which part of a human body, found
// from the skeleton's structure and its rest geometry, names serving only as evidence.
//
// Roles (HumanoidRoleNames): pelvis, spine_1 ... spine_k (the chain between the pelvis and
// the chest, pelvis side first), chest, neck, head, and per side (left_/right_) clavicle,
// upper_arm, forearm, hand, thigh, shin, foot, toes. A skeleton plays a subset of them.
//
// Topology. A branch of joint j is a child subtree of j. Two branches are a pair when they
// have about the same number of joints (difference <= max(1, 25 %)) and reach (the
// farthest joint of the subtree from j, ratio within [0.6, 1.67]). The chest is the first
// joint (preorder) of a branch with a pair of arm branches (>= 2 joints each) and a third
// branch, the neck; the pelvis is a joint with that branch (the spine) and a pair of leg
// branches (>= 2 joints each). Among all (pelvis, chest) choices the one covering the most
// joints wins. So a root bone at the floor above the hips, an `Armature` joint, IK targets
// parented to the root (leaves: no pair of limbs) and extra leaf bones do not matter.
// Geometry: the pelvis->head direction is up, and the legs' far ends must point away from
// it (angle > 120 degrees); otherwise the skeleton is not a humanoid (a quadruped's head
// is ahead of its hips, its legs below them).
//
// Chains. A limb's main chain follows, from the branch's first joint, the child with the
// most joints (then the farthest reach, then the first), helpers last (a duplicated IK/FK
// chain: words ik, mch, ctrl, pole, target, helper in its name, or no vertex weight in its
// subtree where weights are known and some joint carries weight); helper branches are no
// limbs, spine or neck at the pelvis and chest either. Of its segment lengths, the thigh
// (upper arm) is the first or second joint of the chain (after a hip joint or clavicle)
// whose segment is long (>= 0.35 of the chain's longest); when both are, and each is
// followed by a long one, the one whose length ratio to the next is
// nearest 1.05 (legs) or 1.2 (arms) on a log scale (CMU's long clavicle). The shin
// (forearm) and foot (hand) follow it, then the toes; the clavicle is the joint before the
// upper arm. The neck chain's first joint is the neck, its last the head (a last leaf
// with siblings, a head top beside the eyes, is dropped). End bones (leaf
// joints named *end/top/tip/nub*, or leaves carrying no vertex weight when the weights are
// known and at least half the joints carry some) are no role.
//
// Sides. Forward is the horizontal part (perpendicular to up) of foot->toes summed over the
// legs (where the feet lie along the floor: within 45 degrees of it), else of the knees'
// bulge from the hip-ankle lines, else of the forearms summed over both arms (elbows flex
// forward; the sideways parts cancel) when their horizontal parts are >= 30 % of their
// lengths and their sum >= 25 % of the horizontal parts' lengths;
// left = up x forward (right-handed frames); only in a standing pose (each leg, thigh to
// foot, within 35 degrees of down). sides come from that geometry when the two limbs are apart along left by
// more than 2 % of the pelvis-head distance; otherwise from the side words in their names
// (l, left, L, .L, _l; r, right, ...); otherwise the first branch is called left.
// side_certainty: 1 geometry, 0.75 names, 0.5 guessed (the lowest over arms and legs).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_HUMANOID_ROLES_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_HUMANOID_ROLES_H_

#include <string>
#include <utility>
#include <vector>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

struct HumanoidRoles {
  bool humanoid = false;
  std::vector<std::pair<std::string, int>> roles;  // (role, joint) in template order.
  double side_certainty = 0.0;
  std::string side_evidence;  // "geometry", "names" or "guessed" (the weakest of the pairs).
  std::string why_not;        // When not a humanoid: what was found instead.

  int Find(const std::string& role) const;  // The role's joint, or -1.
  // "pelvis, spine_1, chest, ..." or "none".
  std::string RoleList() const;
};

// The template's roles in order, with spine_1 ... spine_<spine_joints>.
std::vector<std::string> HumanoidRoleNames(int spine_joints);

// -1 left, +1 right, 0 no side word in the joint's name.
int NameSide(const std::string& name);

// Body parts: per joint, the index into roles.roles of its nearest ancestor (itself included)
// that plays a role, -1 for none (joints above the pelvis, or a non-humanoid). A part is
// the role's joint and whatever hangs below it until the next role (fingers belong to the
// hand, a forearm's twist bones to the forearm).
std::vector<int> BodyParts(const Skeleton& skeleton, const HumanoidRoles& roles);

// world_positions: the skeleton standing in its rest (or bind) pose, any up axis and facing.
// weighted: per joint, whether it carries vertex weight; empty = unknown.
HumanoidRoles FindHumanoidRoles(const Skeleton& skeleton, const Vector3dVector& world_positions,
                                const std::vector<bool>& weighted = {});

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_HUMANOID_ROLES_H_
