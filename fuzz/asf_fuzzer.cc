// libFuzzer target: ASF text through ParseAsf.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/asf_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mocapsolve::Skeleton skeleton;
  mocapsolve::AsfInfo info;
  (void)mocapsolve::ParseAsf(std::string(reinterpret_cast<const char*>(data), size), "fuzz.asf",
                             &skeleton, &info);
  return 0;
}
