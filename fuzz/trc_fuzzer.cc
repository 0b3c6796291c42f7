// libFuzzer target: TRC text through ParseTrc.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/trc_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mocapsolve::MarkerTrajectories trajectories;
  (void)mocapsolve::ParseTrc(std::string_view(reinterpret_cast<const char*>(data), size),
                             "fuzz.trc", &trajectories);
  return 0;
}
