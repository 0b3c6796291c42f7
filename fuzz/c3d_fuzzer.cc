// libFuzzer target: C3D bytes through ParseC3d.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/c3d_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mocapsolve::MarkerTrajectories trajectories;
  mocapsolve::C3dFileInfo info;
  (void)mocapsolve::ParseC3d(std::string_view(reinterpret_cast<const char*>(data), size),
                             "fuzz.c3d", &trajectories, &info);
  return 0;
}
