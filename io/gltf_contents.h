// What a parsed glTF file holds, counted (for `mocapsolve info`): scenes' nodes, meshes and
// their primitives and vertices, skins, animations. Counts only; reading a character is
// io/gltf_reader.h's.
#ifndef MOCAPSOLVE_IO_GLTF_CONTENTS_H_
#define MOCAPSOLVE_IO_GLTF_CONTENTS_H_

#include <string>
#include <vector>

#include "io/gltf_reader.h"

namespace mocapsolve {

struct GltfContents {
  int nodes = 0;
  int meshes = 0;
  int primitives = 0;
  long long vertices = 0;       // POSITION accessor counts over every primitive.
  int skinned_meshes = 0;       // Meshes instanced by a node that has a skin.
  int skins = 0;
  std::vector<std::string> skin_names;
  int animations = 0;
};

GltfContents CountGltfContents(const GltfDocument& document);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_GLTF_CONTENTS_H_
