// Game-rig glTF files made at test time from a shared Mixamo character (Xbot, Soldier): the
// character's own file with its node graph edited the way game exports leave it, then read
// back through the glTF reader (nothing written to disk, nothing copied into the repository).
// Every perturbation at once:
// - names in a studio's scheme (GameRigScheme): Unreal mannequin (pelvis, spine_01,
//   clavicle_l, upperarm_l, lowerarm_l, hand_l, thigh_l, calf_l, foot_l, ball_l), Rigify
//   (DEF-spine, DEF-upper_arm.L, DEF-shin.R, ... with `.L/.R` or lower-case `.l/.r`),
//   3ds Max Biped (`Bip01 L UpperArm`, spaces), VRM/VRoid (J_Bip_L_UpperArm), or random
//   names (digits only, no side words);
// - the scheme's extra bones, all skin joints that carry no vertex:
//     Unreal: `root` at the floor above the pelvis, ik_foot_root -> ik_foot_l / ik_foot_r
//       at the feet, ik_hand_root -> ik_hand_gun (at the right hand) -> ik_hand_l / _r;
//     Rigify: `root` at the floor, ORG- copies of the arm and leg chains beside the DEF-
//       ones (same parents), MCH-..._ik copies under `root` (only DEF- is skinned); or with
//       rigify_controls, whole-subtree ORG-/_fk/_tweak copies (below);
//     Biped: `Bip01` at the pelvis above `Bip01 Pelvis`, `Bip01 Footsteps` at the floor
//       under it, the clavicles re-parented under `Bip01 Neck` (as Biped has them);
//     VRM: `Root` at the floor;
//     random: `Root` at the floor and the skinned feet (with their toes) re-parented under
//       it, as RobotExpressive's IK feet;
// - the top node (Mixamo's `Armature` / `Character`) with scale `armature_scale` (every node
//   translation below it and the inverse bind matrices rescaled so the character keeps its
//   size) and rotation making the inside z-up (`z_up`) or y-up, and a new node above it with
//   the (non-uniform) scale `above_scale`.
// Every node keeps its world transform (up to the new top scale and `above_scale`); each new
// joint's inverse bind matrix is its world transform's inverse in the rest pose.
// With GAME_RIG_DUMP_DIR set, each rig is also written there as "<file> as <scheme>.glb", to
// look at with the CLI (`mocapsolve info`, `joint_map`).
#ifndef MOCAPSOLVE_TESTS_GAME_RIG_FILES_H_
#define MOCAPSOLVE_TESTS_GAME_RIG_FILES_H_

#include <string>

#include <Eigen/Core>

#include "io/gltf_reader.h"

namespace mocapsolve::testing {

enum class GameRigScheme { kUnreal, kRigify, kBiped, kVrm, kRandom };

struct GameRigOptions {
  GameRigScheme scheme = GameRigScheme::kUnreal;
  bool lower_case_sides = false;  // Rigify `.l/.r`.
  // Rigify as Blender exports it with every bone: instead of the ORG-/MCH- chains, whole
  // copies of each arm's and leg's subtree (fingers and toes included) as ORG-, _fk and
  // _tweak bones (the controls), each placed before the DEF- one among its parent's
  // children: fewer than half the joints carry weight and the copies tie with DEF- in size.
  bool rigify_controls = false;
  double armature_scale = 0.01;
  bool z_up = true;
  Eigen::Vector3d above_scale = Eigen::Vector3d::Ones();
};

// "unreal", "rigify", "biped", "vrm" or "random".
std::string SchemeName(GameRigScheme scheme);

// The scheme's name of a Mixamo joint name (with or without "mixamorig:"), e.g. LeftArm ->
// upperarm_l, DEF-upper_arm.L, Bip01 L UpperArm, J_Bip_L_UpperArm; for kRandom a fixed
// name of digits drawn from the Mixamo name.
std::string GameRigJointName(const std::string& mixamo_name, const GameRigOptions& options);

// Reads `glb` (a Mixamo-named character), edits it as above and reads the result into
// *character (and *document). A failure fails the test.
void MakeGameRig(const std::string& glb, const GameRigOptions& options, GltfDocument* document,
                 GltfCharacter* character);

}  // namespace mocapsolve::testing

#endif  // MOCAPSOLVE_TESTS_GAME_RIG_FILES_H_
