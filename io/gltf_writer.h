// glTF 2.0 writer: the file a character was read from, unchanged, plus one new animation
// holding a Motion of that character (e.g. a retargeted clip), as .glb or as .gltf
// with embedded (data URI) buffers; the output's extension decides.
//
// The source model is copied through tinygltf and the animation appended: one shared
// time accessor (frame k at k / frame_rate seconds, float, with min/max), and per joint
// node a LINEAR rotation channel (VEC4 float) and, for the root joint and every joint
// whose translation differs from its rest offset in some frame (by more than 1e-9 of
// |offset| + 1), a LINEAR translation channel (VEC3 float). The data go at the end of
// buffer 0 (4-byte aligned, one bufferView per accessor); existing buffers, images (as
// stored: buffer views or their URIs) and animations are kept.
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
// Output is written atomically (io/atomic_file.h). Errors: Status naming the output
// path and what is wrong (motion size, frame rate, animation name already used, ...).
#ifndef MOCAPSOLVE_IO_GLTF_WRITER_H_
#define MOCAPSOLVE_IO_GLTF_WRITER_H_

#include <string>

#include "io/gltf_reader.h"
#include "kinematics/motion.h"
#include "kinematics/status.h"

namespace mocapsolve {

// `character` must have been read from `source` (ReadGltfCharacter); `animation_name`
// must be non-empty and not name an existing animation of the source.
Status WriteGltfWithAnimation(const GltfDocument& source, const GltfCharacter& character,
                              const Motion& motion, const std::string& animation_name,
                              const std::string& path);

// The same, into memory: .glb bytes if `binary`, else .gltf JSON text.
Status SerializeGltfWithAnimation(const GltfDocument& source, const GltfCharacter& character,
                                  const Motion& motion, const std::string& animation_name,
                                  bool binary, std::string* bytes);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_GLTF_WRITER_H_
