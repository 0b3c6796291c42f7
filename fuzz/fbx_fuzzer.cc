// libFuzzer target: FBX bytes through ParseFbx (our bounds, assimp in a forked child, then
// assimp and our conversion in this process).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/fbx_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mocapsolve::Skeleton skeleton;
  mocapsolve::Motion motion;
  (void)mocapsolve::ParseFbx(std::string_view(reinterpret_cast<const char*>(data), size),
                             "fuzz.fbx", mocapsolve::FbxReadOptions(), &skeleton, &motion);
  return 0;
}
