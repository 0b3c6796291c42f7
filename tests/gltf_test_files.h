// glTF test files made from a .glb at test time (the real characters are never copied
// into the repository): the same character as a .gltf whose buffers and images are
// separate files, or one whose buffers and images are all data: URIs.
#ifndef MOCAPSOLVE_TESTS_GLTF_TEST_FILES_H_
#define MOCAPSOLVE_TESTS_GLTF_TEST_FILES_H_

#include <string>

namespace mocapsolve::testing {

enum class GltfLayout {
  kSeparateFiles,  // <stem>.bin (one per buffer: <stem>1.bin, ...) and <stem>_image<i>.png|.jpg beside it.
  kDataUris,       // Buffers and images as data: URIs inside the .gltf.
};

// Writes `source` (a .glb or .gltf) as `gltf_path` (.gltf) in `layout`; the node tree,
// meshes, skins, animations and image bytes are unchanged. A failure fails the test.
void WriteGltfVariant(const std::string& source, const std::string& gltf_path, GltfLayout layout);

}  // namespace mocapsolve::testing

#endif  // MOCAPSOLVE_TESTS_GLTF_TEST_FILES_H_
