// Characters as the retarget sees them, made in memory from a glTF character for the
// rest-pose and game-rig fixture tests: as read, or re-posed (A-pose bind, turned facing,
// renamed joints) with the mesh bound again in the new pose.
#ifndef MOCAPSOLVE_TESTS_CHARACTER_VARIANTS_H_
#define MOCAPSOLVE_TESTS_CHARACTER_VARIANTS_H_

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "io/gltf_reader.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"

namespace mocapsolve::testing {

// A character as the retarget sees it, owning its parts.
struct Variant {
  std::string name;
  Skeleton skeleton;
  SkinnedMesh mesh;
  Pose pose;       // Bind and rest pose (world, +y up).
  Pose bind_pose;  // When set: the bind pose (`pose` the rest pose), as the file has them.
};

// The character as read (its own bind and rest poses, mesh as bound).
Variant AsRead(const GltfCharacter& character);

// Joint j's world transform.
Eigen::Isometry3d WorldFromJoint(const FkData& fk, int j);

// `character` re-posed: its rest pose with each of `arms` turned `arm_deg` down toward -y
// (about the axis perpendicular to the arm and the vertical), then the whole figure turned
// `yaw_deg` about +y; the mesh skinned into that pose and bound there (new inverse bind
// matrices), so that pose is its bind and rest pose. Joint names n<random>_<j> when `rename`.
Variant Repose(const GltfCharacter& character, const std::vector<int>& arms, double arm_deg, double yaw_deg,
               bool rename, const std::string& name);

}  // namespace mocapsolve::testing

#endif  // MOCAPSOLVE_TESTS_CHARACTER_VARIANTS_H_
