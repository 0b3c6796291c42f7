// glTF test files made from a .glb at test time (the real characters are never copied
// into the repository): the same character as a .gltf whose buffers and images are
// separate files, or one whose buffers and images are all data: URIs.
#ifndef MOCAPSOLVE_TESTS_GLTF_TEST_FILES_H_
#define MOCAPSOLVE_TESTS_GLTF_TEST_FILES_H_

#include <string>
#include <vector>

namespace mocapsolve::testing {

enum class GltfLayout {
  kSeparateFiles,  // <stem>.bin (one per buffer: <stem>1.bin, ...) and <stem>_image<i>.png|.jpg beside it.
  kDataUris,       // Buffers and images as data: URIs inside the .gltf.
};

// Writes `source` (a .glb or .gltf) as `gltf_path` (.gltf) in `layout`; the node tree,
// meshes, skins, animations and image bytes are unchanged. A failure fails the test.
void WriteGltfVariant(const std::string& source, const std::string& gltf_path, GltfLayout layout);

// Writes a small rigged humanoid without animation as `gltf_path` (.gltf, buffers as a
// data: URI): 19 joints named as Mixamo names them (Hips; Spine, Spine1, Neck, Head;
// LeftShoulder, LeftArm, LeftForeArm, LeftHand and the right side; LeftUpLeg, LeftLeg,
// LeftFoot and the right side), Y up, metres, facing +Z, left = +X; feet at y = 0.05,
// the head joint at 1.6. The upper arms and forearms point out and down by
// `arm_degrees_below_horizontal` (0: T-pose). One skin; a mesh of 21 vertices (one at
// each joint, one at the head's top y = 1.75, one at the left sole y = 0), so the bind-pose
// mesh is 1.75 m tall. A failure fails the test.
void WriteTestCharacter(const std::string& gltf_path, double arm_degrees_below_horizontal);

// The same humanoid as an ASCII FBX (`fbx_path`, centimetres: UnitScaleFactor 1), LimbNode
// models, one mesh geometry skinned by one cluster per joint, no animation.
void WriteTestCharacterFbx(const std::string& fbx_path, double arm_degrees_below_horizontal);

// The test humanoid's joints: name, parent index (-1: root) and offset (metres).
struct TestCharacterJoint {
  std::string name;
  int parent;
  double x, y, z;
};
std::vector<TestCharacterJoint> TestCharacterJoints(double arm_degrees_below_horizontal);

}  // namespace mocapsolve::testing

#endif  // MOCAPSOLVE_TESTS_GLTF_TEST_FILES_H_
