// glTF 2.0 reader (.gltf JSON with embedded or external buffers, and binary .glb): one
// skin of a file as a Skeleton + SkinnedMesh + triangle list, and any of its
// animations sampled into a Motion. Parsing is tinygltf's; everything else (node graph,
// scales, samplers, skinning data) is here. No image is decoded: tinygltf::Image::image
// holds each image's encoded bytes (PNG, JPEG, ...), wherever the file keeps them.
//
// Skeleton (skin 0 unless GltfReadOptions::skin names another, by name or index):
// - Joints: the skin's joints in preorder of the node tree (parents first; siblings in
//   the order of their parent's `children`). A joint's parent is its nearest ancestor
//   node that is a joint. The nodes between two joints (or above the root joint) that
//   are not joints are baked: their constant transform goes into the child's offset and
//   rest rotation, and their animation into the child's pose.
// - Several root joints: the lowest common ancestor node of all of them becomes the
//   skeleton root (a joint that the mesh does not weight, named after the node); if they
//   have none (roots in different scene trees), a synthetic root "gltf_root" at the world
//   origin is added. GltfCharacter::joint_nodes says which node each joint is (-1 for
//   the synthetic root).
// - Pose mapping: with C_j = the similarity (scale s, rotation, translation) of the node
//   chain from joint j's parent joint (exclusive; the scene root for the skeleton root)
//   down to j's node (inclusive), and c_p the accumulated uniform scale of the parent
//   joint (1 for the root),
//       translation_j = c_p * C_j.translation,  rotation_j = R_rest_j^-1 * C_j.rotation,
//   where R_rest_j is the (rest) rotation of the chain above j's node: identity when the
//   parent of j's node is the parent joint. So rotation_j is j's node rotation (the root's
//   included: the non-joint ancestors' rotation, e.g. CesiumMan's Z_UP or Xbot's
//   Armature, is the root's rest rotation) and our world positions and rotations equal
//   glTF's node world transforms with the scale taken out. Skeleton offsets are the
//   translations of the nodes' default TRS; GltfCharacter::rest_pose is that default TRS
//   (rest_pose.rotations = node rotations, not identity).
// - Scale: Skeleton has none. Uniform node scales are accumulated down the tree and
//   baked into offsets/translations (so Xbot's 0.01 Armature gives metres). A
//   non-uniform (or negative) scale is approximated by the cube root of |sx sy sz| with
//   a warning; a `matrix` node is decomposed (polar decomposition, same approximation).
// - Units: glTF's are metres; skeleton.unit() is Metres().
//
// Skinned mesh: every primitive (mode TRIANGLES) of every mesh instanced by a node whose
// `skin` is the chosen skin, merged (vertices in node order, then primitive order). Read:
// POSITION, NORMAL, JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1 (u8/u16 joints; float or
// normalized u8/u16 weights), sparse accessors, indices (u8/u16/u32, or none). Joints
// with zero weight are dropped (an out-of-range joint index is an error only with a
// non-zero weight). Per glTF, the mesh node's own transform is ignored. Unless
// GltfReadOptions::skin chooses a skin, the meshes of the file's other skins whose joints are
// all joints of this skeleton (RobotExpressive's left hand has a skin of its own over the same
// joints) follow, blended into the bind pose with their own inverse bind matrices (a note says
// so); a skin with meshes and other joints is left out with a warning. A mesh without
// NORMAL (Fox) gets area-weighted vertex normals from its triangles (the sum of the
// adjacent triangles' cross products over the vertices at one bind position, normalized),
// with a warning saying so. TEXCOORD_0 (float or normalized u8/u16) is carried as the
// mesh's texcoords (SkinnedMesh::texcoords, glTF's u, v) when every primitive has it.
//   Bind data: glTF skins with v(t) = sum_b w_b G_b(t) IBM_b v0 (G_b the joint node's world
// matrix, scale included). Write IBM_b^-1 = [k_b Q_b | p_b] (uniform scale k_b, rotation
// Q_b) and c_b for joint b's accumulated node scale; then G_b(t) = W_b(t) * scale(c_b) with
// W_b our FK isometry, and with r = median_b(c_b / k_b):
//   joint_from_bind_b = [Q_b | r p_b]^-1,
//   rest_positions    = sum_b w_b [Q_b | r p_b] (c_b IBM_b v0)   (= r v0 when all c_b/k_b = r),
//   rest_normals      = normalized sum_b w_b Q_b normalize(IBM_b^-T n0).
// Skinning this mesh with our FK reproduces glTF's skinning exactly when every c_b/k_b
// equals r (all the test characters); otherwise a warning names the spread. The bind
// pose (FK of bind_pose = [Q_b | r p_b]) generally differs from the rest pose (Soldier).
//
// Animation (ReadGltfAnimation): the channels of one animation (by name or index),
// sampled at frame k at time t0 + k / frame_rate (t0 = the earliest key time, last frame
// at or before the latest key time + 1e-6 s). frame_rate 0 picks the key rate: 1 / the
// smallest key spacing if every spacing is a whole multiple of it (keys may be dropped
// where a curve is constant), else 30 fps. Samplers: STEP, LINEAR (translation/scale
// lerp, rotation slerp) and CUBICSPLINE (Hermite with the in/out tangents scaled by the
// key interval; rotations renormalized). Before the first and after the last key the end
// values hold; a sample time within 1e-5 of the key interval from a key takes that key
// (so float key times k / fps sample back exactly). Channels on translation, rotation and
// scale of joint nodes and of the baked non-joint nodes above them are used; `weights`
// channels (morph targets) and channels on unrelated nodes are ignored. An animated
// scale is used if uniform and constant over the clip, otherwise it is ignored (node
// default kept) with a warning. Rotation series are made sign-continuous.
//
// Errors: Status with one line "<path>: <where>: <what>", e.g. "Xbot.glb: skin 0:
// inverseBindMatrices accessor 7 has 3 matrices for 65 joints". Every index, accessor
// bound, count and number is checked; nothing can crash, allocate without bound, or
// return non-finite values (a sampled clip is limited to 1e7 joint-frames; an accessor
// without a bufferView to 4x the file's data bytes). Files requiring Draco, meshopt or
// mesh quantization are refused. Weights that do not sum to 1 (RobotExpressive) are
// normalized, as three.js does.
#ifndef MOCAPSOLVE_IO_GLTF_READER_H_
#define MOCAPSOLVE_IO_GLTF_READER_H_

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"

namespace tinygltf {
class Model;
}

namespace mocapsolve {

// A parsed glTF file (tinygltf's model, shared and immutable), read once and used for
// the character and any number of animations.
class GltfDocument {
 public:
  GltfDocument() = default;
  // .glb if the file starts with the "glTF" magic, JSON otherwise (external buffers are
  // resolved beside the file).
  static Status Read(const std::string& path, GltfDocument* document);
  // Bytes held in memory; error messages name `name_for_errors`; `base_dir` resolves
  // external buffer URIs ("" = relative to the working directory).
  static Status Parse(const std::string& bytes, const std::string& name_for_errors,
                      const std::string& base_dir, GltfDocument* document);

  bool loaded() const { return model_ != nullptr; }
  const std::string& name() const { return name_; }
  // The tinygltf model (for io/ and tests; include <tiny_gltf.h> to use it).
  const tinygltf::Model& model() const { return *model_; }

 private:
  std::shared_ptr<const tinygltf::Model> model_;
  std::string name_;
};

struct GltfReadOptions {
  std::string skin;  // Skin name or index; "" = skin 0.
};

struct GltfCharacter {
  Skeleton skeleton;            // Metres.
  SkinnedMesh mesh;             // Bound to `skeleton` (see the header comment).
  Eigen::Matrix3Xi triangles;   // 3 x #T vertex indices into `mesh`, glTF winding.
  Pose rest_pose;               // The nodes' default TRS.
  Pose bind_pose;               // FK(bind_pose) = inverse bind matrices, scale removed.
  std::vector<std::string> animation_names;  // Every animation of the file ("" if unnamed).
  int skin = 0;                              // Index of the skin read.
  std::vector<int> joint_nodes;     // #J glTF node of each joint, -1 for "gltf_root".
  std::vector<int> skin_joints;     // Skeleton joint of each entry of skin.joints.
  double bind_scale = 1.0;          // r above (rest_positions = r * glTF bind vertices).
  std::vector<std::string> warnings;  // Approximations made (non-uniform scales, ...).
};

Status ReadGltfCharacter(const GltfDocument& document, const GltfReadOptions& options,
                         GltfCharacter* character);
// Convenience: GltfDocument::Read + ReadGltfCharacter.
Status ReadGltfCharacter(const std::string& path, const GltfReadOptions& options,
                         GltfCharacter* character);

struct GltfAnimationOptions {
  std::string animation;    // Name or index; "" = animation 0.
  double frame_rate = 0.0;  // Frames per second; 0 = the key rate if uniform, else 30.
};

// Index of the animation `selector` names (see GltfAnimationOptions::animation) or an
// error listing the animations.
Status FindGltfAnimation(const GltfDocument& document, const std::string& selector, int* index);

// Samples an animation for a character read from the same document. *warnings (may be
// null) receives the channels that were ignored or approximated.
Status ReadGltfAnimation(const GltfDocument& document, const GltfCharacter& character,
                         const GltfAnimationOptions& options, Motion* motion,
                         std::vector<std::string>* warnings = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_GLTF_READER_H_
