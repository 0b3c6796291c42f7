// libFuzzer target: glTF JSON or GLB bytes through GltfDocument::Parse (our bounds, then
// tinygltf), then the character (skin, meshes) and animation 0 through our reader.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/gltf_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mocapsolve;
  GltfDocument document;
  // base_dir "/nonexistent": relative buffer URIs resolve to nothing (tinygltf only reads).
  if (!GltfDocument::Parse(std::string(reinterpret_cast<const char*>(data), size), "fuzz.glb",
                           "/nonexistent", &document)
           .ok()) {
    return 0;
  }
  GltfCharacter character;
  if (!ReadGltfCharacter(document, GltfReadOptions(), &character).ok()) return 0;
  if (character.animation_names.empty()) return 0;
  Motion motion;
  (void)ReadGltfAnimation(document, character, GltfAnimationOptions(), &motion);
  return 0;
}
