#include "io/gltf_contents.h"

#include <set>

#include <tiny_gltf.h>

namespace mocapsolve {

GltfContents CountGltfContents(const GltfDocument& document) {
  GltfContents out;
  if (!document.loaded()) return out;
  const tinygltf::Model& model = document.model();
  out.nodes = static_cast<int>(model.nodes.size());
  out.meshes = static_cast<int>(model.meshes.size());
  out.skins = static_cast<int>(model.skins.size());
  out.animations = static_cast<int>(model.animations.size());
  for (const tinygltf::Skin& skin : model.skins) out.skin_names.push_back(skin.name);
  for (const tinygltf::Mesh& mesh : model.meshes) {
    out.primitives += static_cast<int>(mesh.primitives.size());
    for (const tinygltf::Primitive& primitive : mesh.primitives) {
      const auto position = primitive.attributes.find("POSITION");
      if (position == primitive.attributes.end()) continue;
      if (position->second >= 0 && position->second < static_cast<int>(model.accessors.size())) {
        out.vertices += static_cast<long long>(model.accessors[position->second].count);
      }
    }
  }
  std::set<int> skinned;
  for (const tinygltf::Node& node : model.nodes) {
    if (node.skin >= 0 && node.mesh >= 0 && node.mesh < out.meshes) skinned.insert(node.mesh);
  }
  out.skinned_meshes = static_cast<int>(skinned.size());
  return out;
}

}  // namespace mocapsolve
