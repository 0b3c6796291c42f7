// libFuzzer target: the project's JSON reader (ParseJson), then the two file formats built
// on it against a fixed skeleton: marker sets (ParseMarkerSet) and edit files
// (ParseEditFile). One target, since the bytes are JSON for all three.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz/fuzz_skeleton.h"
#include "io/edit_file.h"
#include "io/json_reader.h"
#include "io/marker_set_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  mocapsolve::JsonNode root;
  if (!mocapsolve::ParseJson(text, "fuzz.json", &root).ok()) return 0;
  const mocapsolve::Skeleton& skeleton = mocapsolve::FuzzSkeleton();
  mocapsolve::MarkerSet marker_set;
  (void)mocapsolve::ParseMarkerSet(text, "fuzz.json", skeleton, &marker_set);
  std::vector<mocapsolve::EditFileEntry> edits;
  (void)mocapsolve::ParseEditFile(text, "fuzz.json", skeleton, &edits);
  return 0;
}
