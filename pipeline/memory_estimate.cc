#include "pipeline/memory_estimate.h"

#include <cstdio>

namespace mocapsolve {
namespace {

// Measured 2026-12-07 and -08 (BENCHMARKS.md, "Memory against the take's length"); KB, MB.
constexpr double kPipelineBaseMb = 28.0;          // x1 (1,854 frames): 49,684 KB (fourth pass).
constexpr double kPipelineSharedKb = 5.3;         // 11.3 KB per frame from x1 to x16,
constexpr double kPipelinePerMarkerKb = 6.0 / 41;  // of which ~6.0 KB marker samples (heaptrack).
constexpr double kWindowedSharedKb = 1.2;         // Windowed (take_windows.h), x233: 1,241 MB = 240 MB (a
constexpr double kWindowedPerMarkerKb = 1.2 / 41;  // window) + 2.4 KB per frame: the compact take, the samples.
constexpr double kClipBaseMb = 23.0;              // solve --mode=clip, 300 and 1,854 frames:
constexpr double kClipPerMarkerKb = 184.0 / 41;   // 184 KB per frame, its residual blocks per marker.
constexpr double kFilterBaseMb = 15.0;            // filter --levels=2 of solved.bvh, x1 and x4:
constexpr double kFilterKb = 10.7;                // 10.7 KB per frame (31 joints; reading, writing).
constexpr double kPipelineFilterKb = 1.4;         // pipeline --filter_levels=2, x1 and x4: 16.6 KB.
constexpr double kGreenBaseMb = 16.5;             // propagate --method=green, x1 and x4:
constexpr double kGreenKb = 4.7;                  // 4.7 KB per frame (31 joints).

// 431982 -> "431,982".
std::string Grouped(long long value) {
  std::string digits = std::to_string(value), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

}  // namespace

MemoryEstimate& MemoryEstimate::Add(const MemoryEstimate& other) {
  method += ", " + other.method;
  kb_per_frame += other.kb_per_frame;
  return *this;
}

MemoryEstimate PipelineMemory(int frames, int markers) {
  return {"the pipeline's per-frame stages", frames, markers, kPipelineBaseMb,
          kPipelineSharedKb + kPipelinePerMarkerKb * markers};
}

MemoryEstimate WindowedPipelineMemory(int frames, int window, int markers) {
  const MemoryEstimate one = PipelineMemory(window, markers);
  return {"the pipeline's windows", frames, markers, one.mb(), kWindowedSharedKb + kWindowedPerMarkerKb * markers};
}

void AddPerWindow(const MemoryEstimate& other, int frames, MemoryEstimate* estimate) {
  estimate->method += ", " + other.method;
  estimate->base_mb += frames * other.kb_per_frame / 1024.0;
}

MemoryEstimate ClipSolveMemory(int frames, int markers) {
  return {"the clip solve", frames, markers, kClipBaseMb, kClipPerMarkerKb * markers};
}

MemoryEstimate PyramidFilterMemory(int frames) {
  return {"the pyramid filter", frames, 0, kFilterBaseMb, kFilterKb};
}

MemoryEstimate PipelineFilterMemory(int frames) {
  return {"the filter", frames, 0, 0.0, kPipelineFilterKb};
}

MemoryEstimate GreenFunctionMemory(int frames) {
  return {"the Green's function", frames, 0, kGreenBaseMb, kGreenKb};
}

Status CheckMemoryLimit(const MemoryEstimate& estimate, double limit_mb, const std::string& input) {
  if (!(limit_mb > 0.0) || estimate.mb() <= limit_mb) return Status::Ok();
  char figures[160];
  std::snprintf(figures, sizeof figures, " MB (%.0f MB + %.1f KB per frame), over the limit; nothing was done",
                estimate.base_mb, estimate.kb_per_frame);
  std::string counts = Grouped(estimate.frames) + " frames";
  if (estimate.markers > 0) counts += ", " + std::to_string(estimate.markers) + " markers";
  return Status::Error("--memory_mb=" + Grouped(static_cast<long long>(limit_mb + 0.5)) + ": " + estimate.method +
                       " on " + input + " (" + counts + ") would need about " +
                       Grouped(static_cast<long long>(estimate.mb() + 0.5)) + figures);
}

}  // namespace mocapsolve
