#include "tests/gltf_test_files.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "io/gltf_reader.h"
#include "tests/test_support.h"
#include "viewer/view_page.h"

namespace mocapsolve::testing {
namespace {

// Images are written by WriteGltfVariant itself: tinygltf keeps each image's `uri`.
bool KeepImageUri(const std::string*, const std::string*, const tinygltf::Image*, bool, std::string*, void*) {
  return false;
}

}  // namespace

void WriteGltfVariant(const std::string& source, const std::string& gltf_path, GltfLayout layout) {
  GltfDocument document;  // Keeps every image's encoded bytes (gltf_reader.h).
  const Status status = GltfDocument::Read(source, &document);
  ASSERT_TRUE(status.ok()) << status.message();
  tinygltf::Model model = document.model();
  const size_t slash = gltf_path.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : gltf_path.substr(0, slash);
  std::string stem = gltf_path.substr(slash == std::string::npos ? 0 : slash + 1);
  stem = stem.substr(0, stem.rfind('.'));
  const bool files = layout == GltfLayout::kSeparateFiles;
  for (size_t i = 0; i < model.images.size(); ++i) {
    tinygltf::Image& image = model.images[i];
    ASSERT_FALSE(image.image.empty()) << source << ": image " << i << " has no bytes";
    const bool jpeg = image.image.size() > 2 && image.image[0] == 0xff && image.image[1] == 0xd8;
    const std::string bytes(image.image.begin(), image.image.end());
    if (files) {
      image.uri = stem + "_image" + std::to_string(i) + (jpeg ? ".jpg" : ".png");
      WriteTextFile(dir + "/" + image.uri, bytes);
    } else {
      image.uri = std::string("data:image/") + (jpeg ? "jpeg" : "png") + ";base64," + Base64(bytes);
    }
    image.bufferView = -1;
    image.mimeType.clear();
    image.image.clear();
  }
  for (size_t b = 0; b < model.buffers.size(); ++b) {
    model.buffers[b].uri = files ? stem + (b == 0 ? "" : std::to_string(b)) + ".bin" : "";
  }
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(&KeepImageUri, nullptr);
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&model, gltf_path, /*embedImages=*/false, /*embedBuffers=*/!files,
                                          /*prettyPrint=*/true, /*writeBinary=*/false))
      << gltf_path << ": tinygltf could not write it";
}

}  // namespace mocapsolve::testing
