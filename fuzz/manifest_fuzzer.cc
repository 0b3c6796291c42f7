// libFuzzer target: batch manifests (ParseManifest) against a fixed set of pipeline
// options, then the manifest written back out (FormatManifest). Only the form is parsed:
// no file the manifest names is opened.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "batch/manifest.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const mocapsolve::BatchOptions* pipeline_options = [] {
    auto* options = new mocapsolve::BatchOptions;
    (void)mocapsolve::ParsePipelineOptions(
        "{\"filter_levels\": 0, \"gate_torso_deg\": 15, \"reference\": \"tracker\", \"animation_only\": false}",
        options);
    return options;
  }();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  mocapsolve::BatchManifest manifest;
  if (!mocapsolve::ParseManifest(text, "fuzz/M.json", *pipeline_options, &manifest).ok()) return 0;
  (void)mocapsolve::FormatManifest(manifest, *pipeline_options);
  for (const mocapsolve::BatchTake& take : manifest.takes) {
    (void)mocapsolve::GivenOptionsJson(manifest, take);
    (void)mocapsolve::ResolvedOptionsJson(manifest, take);
  }
  return 0;
}
