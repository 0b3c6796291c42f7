// Floor IK bones: IK targets and pole bones parented to a root bone at the floor, driven for
// the retarget by forward kinematics of the anatomical chain they belong to.
//
// Game rigs parent the IK targets to a root bone at the floor, not to the limbs: Unreal's
// ik_foot_l / ik_foot_r (under ik_foot_root), RobotExpressive's Foot.L / Foot.R and
// PoleTarget.L / .R (under its root bone `Bone`), Rigify's IK and MCH bones. An engine's IK
// solver puts the foot at its target and turns the leg to reach it; a glTF or FBX file has no
// such solver, so whatever is skinned or parented to the IK bone (RobotExpressive's foot
// meshes) moves with it alone. The retarget solve turns joints and moves the root only
// (retarget_frame_solver.h), so an IK foot would move only with the root while its leg turns:
// the shin (knee -> foot) cannot point as the source's and the foot slides with the body.
//
// Detection (FindFloorIkBones), on the skeleton standing in a pose (positions x_j) with its
// humanoid roles. The floor side F starts as the strict ancestors of the pelvis (the root bone,
// an `Armature` joint). Visiting joints parents first, a joint j with parent p in F whose
// subtree does not hold the pelvis is an IK bone when the body (the pelvis' subtree) is nearer
// to it than p is:
//     d_j = min( min_a |x_j - x_a|, min_v |x_j - v| ) < |x_j - x_p|,
// a over the joints of the pelvis' subtree (with a mesh: those whose subtree carries vertex
// weight, so an unskinned duplicate chain such as Rigify's ORG- bones, lying on the skinned
// DEF- chain, is no anchor), v over the mesh's vertices (bind pose) whose heaviest joint is one
// of them; the joint of the minimum (a, or v's heaviest joint) is its anchor. Otherwise j
// joins F (an ik_foot_root at the floor's origin) and its children are examined in turn. So
// a foot target at the ankle follows the shin whose surface ends there (or the foot joint it
// sits on, Unreal's), a pole target in front of the knee follows the
// knee, and a bone at the root (a root helper, a prop at the origin) stays. Non-humanoids (no
// pelvis) and skeletons rooted at the pelvis have none (and cost nothing).
//
// The math. With G_j = world_from_joint_j = G_parent * T(t_j) * R_rest_j * R_j (skeleton.h):
//   the solve character (MakeFloorIkSolveCharacter): each IK bone j re-parented under its
//     anchor a with its rest pose's relative transform, t'_j and R'_j from
//       G_a^rest * T(t'_j) * R_rest_j * R'_j = G_j^rest,
//     i.e. t'_j = Q_a^T (x_j - x_a), R'_j = R_rest_j^-1 Q_a^-1 Q_j (Q the world rotations; the
//     skeleton offset is t'_j); the same in the bind pose for the bind pose. Joints re-ordered
//     parents first (preorder; an anchor's IK bones after its own children). The mesh keeps its
//     vertices and inverse bind matrices (its joint indices follow the order), so the surface
//     at the bind pose is the same and every solver runs unchanged (rotations and the root);
//     the IK bone then follows its anchor rigidly, G_j(f) = G_a(f) T(t'_j) R_rest_j R'_j(f), its
//     own rotation R'_j(f) solved as any joint's when it carries vertices.
//   back on the character (FloorIkMotionOnCharacter): every other joint keeps its local
//     rotation and translation; an IK bone with its original parent p gets
//       t_j(f) = Q_p(f)^T (x_j(f) - x_p(f)),   R_j(f) = R_rest_j^-1 Q_p(f)^-1 Q_j(f),
//     a translation and a rotation key per frame: the targets where the anatomical chain puts
//     them, which is what an engine's IK rig expects of a clip (its IK then reproduces the legs,
//     and a player without IK shows the same pose). World positions of every joint are those of
//     the solve, exactly (to rounding).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_FLOOR_IK_BONES_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_FLOOR_IK_BONES_H_

#include <string>
#include <vector>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"
#include "problems/retarget/humanoid_roles.h"

namespace mocapsolve {

struct FloorIkBones {
  std::vector<int> bones;    // IK bones (the tops of their subtrees), character joint indices.
  std::vector<int> anchors;  // The joint each follows, character joint indices.
  bool empty() const { return bones.empty(); }
  // "Foot.L on LowerLeg.L_end, ..." (names from `skeleton`).
  std::string Describe(const Skeleton& skeleton) const;
};

// x: #J world positions of the skeleton in its bind pose (the pose of the mesh's rest
// positions); roles: its humanoid roles (a non-humanoid gives none); mesh: may be null.
FloorIkBones FindFloorIkBones(const Skeleton& skeleton, const Vector3dVector& x, const HumanoidRoles& roles,
                              const SkinnedMesh* mesh);

// The character the solve sees: IK bones under their anchors, joints in the new order.
struct FloorIkSolveCharacter {
  Skeleton skeleton;
  SkinnedMesh mesh;
  Pose bind_pose, rest_pose;
  std::vector<int> character_of_solve;  // Solve joint -> character joint.
  std::vector<int> solve_of_character;  // Character joint -> solve joint.
};

// bind_pose: the pose of the mesh's inverse bind matrices; rest_pose: the pose the offsets
// are taken in (the clip's start). Errors: sizes that do not fit.
Status MakeFloorIkSolveCharacter(const Skeleton& skeleton, const SkinnedMesh& mesh, const Pose& bind_pose,
                                 const Pose& rest_pose, const FloorIkBones& ik, FloorIkSolveCharacter* solve);

// A pose of the solve character from a pose of the character (world transforms the same).
Pose FloorIkPoseOnSolveCharacter(const Skeleton& skeleton, const FloorIkBones& ik,
                                 const FloorIkSolveCharacter& solve, const Pose& pose);

// A pose of the character from a pose of its solve character (world transforms the same).
Pose FloorIkPoseOnCharacter(const Skeleton& skeleton, const FloorIkBones& ik, const FloorIkSolveCharacter& solve,
                            const Pose& solve_pose);

// Every frame of `motion` (on solve.skeleton) as FloorIkPoseOnCharacter.
Motion FloorIkMotionOnCharacter(const Skeleton& skeleton, const FloorIkBones& ik, const FloorIkSolveCharacter& solve,
                                const Motion& motion);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_FLOOR_IK_BONES_H_
