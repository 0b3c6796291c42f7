// libFuzzer target: BVH text through ParseBvh (the in-memory entry point of ReadBvh).
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/bvh_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mocapsolve::Skeleton skeleton;
  mocapsolve::Motion motion;
  (void)mocapsolve::ParseBvh(std::string(reinterpret_cast<const char*>(data), size), "fuzz.bvh",
                             &skeleton, &motion);
  return 0;
}
