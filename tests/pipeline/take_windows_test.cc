// The windows a long take runs in (pipeline/take_windows.h): cores that cover every frame
// once, in order, as equal as can be; context clamped to the take; one window when the
// take fits.
#include "pipeline/take_windows.h"

#include <gtest/gtest.h>

#include "pipeline/memory_estimate.h"

namespace mocapsolve {
namespace {

TEST(TakeWindows, CoresCoverEveryFrameOnceWithContextEachSide) {
  for (int frames : {1, 199, 200, 201, 600, 1854, 431982}) {
    const std::vector<FrameWindow> windows = TakeWindows(frames, 200, 50);
    ASSERT_EQ(static_cast<int>(windows.size()), (frames + 199) / 200) << frames;
    int next = 0;
    int smallest = frames, largest = 0;
    for (const FrameWindow& w : windows) {
      EXPECT_EQ(w.core_first, next) << frames;
      EXPECT_GE(w.core_last, w.core_first);
      EXPECT_EQ(w.first, std::max(0, w.core_first - 50));
      EXPECT_EQ(w.last, std::min(frames - 1, w.core_last + 50));
      smallest = std::min(smallest, w.core_last - w.core_first + 1);
      largest = std::max(largest, w.core_last - w.core_first + 1);
      next = w.core_last + 1;
    }
    EXPECT_EQ(next, frames);
    EXPECT_LE(largest, 200);
    EXPECT_LE(largest - smallest, 1) << frames;
  }
  const std::vector<FrameWindow> whole = TakeWindows(600, 600, 50);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_EQ(whole[0].first, 0);
  EXPECT_EQ(whole[0].last, 599);
  EXPECT_TRUE(TakeWindows(0, 200, 50).empty());
}

// --memory_mb's estimate of a windowed take: one window's stages as the base and the
// outputs' few KB per frame of the take, not the whole take's stages.
TEST(TakeWindows, MemoryEstimateIsAWindowPlusTheOutputs) {
  TakePipelineOptions options;  // 18,000-frame windows with 600 of context.
  options.repair.reference_kind = ReferenceKind::kTracker;  // The command's default.
  const MemoryEstimate short_take = TakeMemory(1854, 41, options);
  EXPECT_DOUBLE_EQ(short_take.mb(), PipelineMemory(1854, 41).mb());  // Whole, as before.
  const MemoryEstimate hour = TakeMemory(431982, 41, options);
  EXPECT_EQ(hour.method, "the pipeline's windows");
  EXPECT_DOUBLE_EQ(hour.base_mb, PipelineMemory(19200, 41).mb());
  EXPECT_LE(hour.kb_per_frame, 3.0);
  EXPECT_LT(hour.mb(), 1500.0);
  EXPECT_LT(hour.mb(), PipelineMemory(431982, 41).mb() / 3);
  options.filter_levels = 2;
  EXPECT_DOUBLE_EQ(TakeMemory(431982, 41, options).kb_per_frame, hour.kb_per_frame);  // The filter runs per window.
}

}  // namespace
}  // namespace mocapsolve
