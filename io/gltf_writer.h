// glTF 2.0 writer: the file a character was read from, unchanged, plus one new animation
// holding a Motion of that character (e.g. a retargeted clip), as .glb or as .gltf
// with embedded (data URI) buffers; the output's extension decides.
//
// The source model is copied through tinygltf and the animation added as the first one
// (the clip readers open by default: `convert`, `info`, `view`, three.js's clips[0]; the
// character's own animations follow, in their order): one shared
// time accessor (frame k at k / frame_rate seconds, float, with min/max), and per joint
// node a LINEAR rotation channel (VEC4 float) and, for the root joint and every joint
// whose translation differs from its rest offset in some frame (by more than 1e-9 of
// |offset| + 1), a LINEAR translation channel (VEC3 float). The data go at the end of
// buffer 0 (4-byte aligned, one bufferView per accessor); existing animations are kept, and
// so are buffers and images: in a .glb all inside it (as SerializeGltfAsGlb below), in a
// .gltf as stored (buffers as data: URIs; images as buffer views or their URIs).
//
// The reader's baking is undone (gltf_reader.h): with A_j the default-transform
// similarity of the nodes between j's parent joint and j's node and c_p the parent's
// accumulated rest scale, node rotation = A_j.rotation^-1 * R_rest_j * rotation_j and
// node translation = A_j.rotation^-1 (translation_j / c_p - A_j.translation) / A_j.scale,
// so reading the new animation back gives the Motion again (to float precision). Scales
// are not animated (the nodes keep their default scale). A joint node given by a
// `matrix` is rewritten as the equivalent TRS (channels cannot target a matrix node);
// a matrix that is not a uniform-scale similarity is an error. A synthetic "gltf_root"
// cannot be written: the motion must leave it at rest.
//
// Animation only (GltfWriteOptions::animation_only): the file holds just what an
// application needs to play the clip on the character it already has loaded, not a copy of
// the character: the joint nodes of the character's skin and their ancestors (names,
// default TRS or matrix as in the source, children among them; meshes, cameras and the
// nodes that only hold them are dropped), the skin itself (joints, skeleton and
// inverseBindMatrices: 64 bytes a joint; no node references it, as a glTF skin needs a mesh
// node, so the validator reports it as unused, an info), one scene of the kept top-level
// nodes, and the new animation with the same channels and keys as in the full file, except
// that a channel whose keys are all equal (the fingers of a skeleton-only source: half of
// Xbot's channels) has one key at time 0, which glTF holds for the whole clip. No
// meshes, materials, textures, images, samplers, other animations or vertex buffers; the
// data (animation keys and inverse bind matrices) are copied into one buffer. The skin is
// kept because Blender's importer makes an armature only of a skin's joints (other nodes
// become empties) and computes the bones' rest from the inverse bind matrices (its default
// "guess original bind pose"), so the animation-only import gets the same armature and
// rest pose as the character's and its action applies to the character's armature by bone
// name (scripts/apply_animation_gltf.py). three.js binds animation tracks by node name, so
// GLTFLoader's clip plays on the character's scene as it is (when node names are unique:
// GLTFLoader renames repeated ones). CMU 02_05 onto Xbot: 1.05 MB against 3.81 MB (README).
//
// Output is written atomically (io/atomic_file.h). Errors: Status naming the output
// path and what is wrong (motion size, frame rate, animation name already used, ...).
#ifndef MOCAPSOLVE_IO_GLTF_WRITER_H_
#define MOCAPSOLVE_IO_GLTF_WRITER_H_

#include <string>

#include "io/gltf_reader.h"
#include "kinematics/compact_motion.h"
#include "kinematics/motion.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct GltfWriteOptions {
  // The viewer's pages (the files commands deliver keep the full form): the new
  // animation's rotations as normalized SHORT VEC4 (allowed by glTF 2.0 for rotation
  // outputs; 3e-5 per component) instead of float, half their bytes, and a channel whose
  // stored value is the same in every frame (a finger the take does not move) as one key
  // at time 0, which holds over the clip (glTF and three.js keep a track's end values).
  bool compact = false;
  // Skeleton, skin and the new animation only (see above), not the whole character.
  bool animation_only = false;
};

// `character` must have been read from `source` (ReadGltfCharacter); `animation_name`
// must be non-empty and not name an existing animation of the source.
Status WriteGltfWithAnimation(const GltfDocument& source, const GltfCharacter& character,
                              const Motion& motion, const std::string& animation_name,
                              const std::string& path, const GltfWriteOptions& options = {});
// The same from a CompactMotion (kinematics/compact_motion.h), read one joint of one frame
// at a time: a long take is not expanded whole to be written.
Status WriteGltfWithAnimation(const GltfDocument& source, const GltfCharacter& character,
                              const CompactMotion& motion, const std::string& animation_name,
                              const std::string& path, const GltfWriteOptions& options = {});

// The same, into memory: .glb bytes if `binary`, else .gltf JSON text. A .glb is
// self-contained as SerializeGltfAsGlb makes it (a .gltf keeps its images' URIs).
Status SerializeGltfWithAnimation(const GltfDocument& source, const GltfCharacter& character,
                                  const Motion& motion, const std::string& animation_name,
                                  bool binary, std::string* bytes, const GltfWriteOptions& options = {});
Status SerializeGltfWithAnimation(const GltfDocument& source, const GltfCharacter& character,
                                  const CompactMotion& motion, const std::string& animation_name,
                                  bool binary, std::string* bytes, const GltfWriteOptions& options = {});

// The source as one self-contained .glb (bytes), e.g. a .gltf with external .bin files,
// images beside it or data: URIs, for a page that has no files beside it (`mocapsolve
// view --character=X.gltf`): every buffer's bytes are appended to buffer 0 (the BIN
// chunk; each buffer starting at a multiple of 4 bytes) and the buffer views re-pointed;
// every image given by a URI (a file or a data: URI) moves into a buffer view of its own,
// its mimeType from its bytes' signature (PNG, JPEG, WebP), else as stated, else from its
// extension. Everything else is kept as tinygltf writes it. Errors: an image that could
// not be read (a missing file), named by index and URI.
Status SerializeGltfAsGlb(const GltfDocument& source, std::string* glb);

// Re-expresses a motion of another skeleton that has the character's joints (same names
// and parents, e.g. a BVH converted from the character and edited) in the character's
// joint order and rest rotations, so that FK is unchanged:
//   rotation_j = R_rest_char_j^-1 * R_rest_source_j * rotation_source_j,
//   translation_j = scale * translation_source_j,
// scale = source.unit / character.unit when both are known, else 1 (a BVH states no
// unit: it is taken to be the character's). Joints of the source the character does not
// have are dropped; a character joint missing from the source, a different parent, or an
// offset that differs by more than 1e-3 of the character's size is an error naming the
// joint. The synthetic "gltf_root" may be missing (it stays at rest).
Status MotionForCharacter(const Skeleton& source, const Motion& motion, const GltfCharacter& character,
                          Motion* out);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_GLTF_WRITER_H_
