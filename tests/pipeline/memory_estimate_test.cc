// The memory estimates of the whole-clip methods (pipeline/memory_estimate.h) and the
// --memory_mb check, and the take's size read without its samples (io/marker_file.h).
#include "pipeline/memory_estimate.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/c3d_reader.h"
#include "io/marker_file.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

TEST(MemoryEstimate, BasePlusPerFrameAndMarker) {
  const MemoryEstimate one = PipelineMemory(1000, 41), two = PipelineMemory(2000, 41);
  EXPECT_DOUBLE_EQ(two.mb() - one.mb(), one.mb() - one.base_mb);  // Linear in frames.
  EXPECT_NEAR(one.kb_per_frame, 11.3, 0.05);  // The figure measured on CMU 02_05 (41 markers).
  EXPECT_GT(PipelineMemory(1000, 82).kb_per_frame, one.kb_per_frame);  // More markers, more samples.
  // The one-hour take at 120 Hz: about 4.8 GB (BENCHMARKS.md).
  EXPECT_NEAR(PipelineMemory(431982, 41).mb(), 4795.0, 100.0);
  MemoryEstimate both = PipelineMemory(1000, 41);
  both.Add(ClipSolveMemory(1000, 41));
  EXPECT_DOUBLE_EQ(both.kb_per_frame, one.kb_per_frame + ClipSolveMemory(1000, 41).kb_per_frame);
  EXPECT_EQ(both.method, "the pipeline's per-frame stages, the clip solve");
  EXPECT_GT(PyramidFilterMemory(1000).mb(), PyramidFilterMemory(10).mb());
  EXPECT_GT(GreenFunctionMemory(1000).mb(), GreenFunctionMemory(10).mb());
}

TEST(MemoryEstimate, LimitRefusesWithTheFigure) {
  const MemoryEstimate clip = ClipSolveMemory(431982, 41);
  EXPECT_TRUE(CheckMemoryLimit(clip, 0.0, "take.c3d").ok());  // No limit.
  EXPECT_TRUE(CheckMemoryLimit(clip, clip.mb() + 1.0, "take.c3d").ok());
  const Status refused = CheckMemoryLimit(clip, 1500.0, "take.c3d");
  ASSERT_FALSE(refused.ok());
  EXPECT_THAT(refused.message(), HasSubstr("--memory_mb=1,500: the clip solve on take.c3d (431,982 frames, 41 markers) "
                                           "would need about 77,6"));
  EXPECT_THAT(refused.message(), HasSubstr("(23 MB + 184.0 KB per frame), over the limit; nothing was done"));
  EXPECT_EQ(refused.message().find('\n'), std::string::npos);
}

// The size of a take from its header: the frames and labels, no samples decoded.
TEST(MarkerFileShape, C3dHeaderAndTrcWhole) {
  MarkerTrajectories take({"a", "b", "c"}, 250);
  take.frame_rate = 120.0;
  take.unit = LengthUnitFromName("mm");
  for (int f = 0; f < 250; ++f) take.SetSample(f, f % 3, Eigen::Vector3d(f, 1.0, 2.0));
  for (const std::string extension : {".c3d", ".trc"}) {
    const std::string path = testing::TempPath("take" + extension);
    const Status written = WriteMarkerFile(path, take);
    ASSERT_TRUE(written.ok()) << written.message();
    MarkerFileShape shape;
    ASSERT_TRUE(ReadMarkerFileShape(path, &shape).ok()) << extension;
    EXPECT_EQ(shape.frames, 250) << extension;
    EXPECT_EQ(shape.markers, 3) << extension;
    EXPECT_DOUBLE_EQ(shape.frame_rate, 120.0) << extension;
  }
  C3dReadOptions header_only;
  header_only.header_only = true;
  MarkerTrajectories labels;
  C3dFileInfo info;
  ASSERT_TRUE(ReadC3d(testing::TempPath("take.c3d"), &labels, &info, header_only).ok());
  EXPECT_EQ(labels.num_frames(), 0);
  EXPECT_EQ(labels.num_markers(), 3);
  EXPECT_EQ(info.frames, 250);
  MarkerFileShape shape;
  EXPECT_FALSE(ReadMarkerFileShape(testing::TempPath("missing.c3d"), &shape).ok());
}

}  // namespace
}  // namespace mocapsolve
