// Smoke tests of `mocapsolve filter`, `bands` and `blend` on the project's demo clip and
// synthesized markers, with the bad-input cases that must fail with one line.
#include <sys/stat.h>

#include <algorithm>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/marker_file.h"
#include "io/motion_file.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

double MaxRotationDifference(const Motion& a, const Motion& b) {
  double worst = 0.0;
  for (int f = 0; f < a.num_frames(); ++f) {
    for (size_t j = 0; j < a.frames[f].rotations.size(); ++j) {
      worst = std::max(worst, AngularDistance(a.frames[f].rotations[j], b.frames[f].rotations[j]));
    }
  }
  return worst;
}

class SignalCli : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk.bvh");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=90 --fps=30", &output), 0)
        << output;
  }
  Motion Read(const std::string& path) {
    Skeleton skeleton;
    Motion motion;
    EXPECT_TRUE(ReadMotionFile(path, MotionFileOptions(), &skeleton, &motion).ok()) << path;
    return motion;
  }
  std::string demo_;
};

TEST_F(SignalCli, FilterMotionAndMarkers) {
  std::string output;
  const std::string out = testing::TempPath("smooth.bvh");
  ASSERT_EQ(testing::RunCli("filter --motion=" + demo_ + " --levels=2 --out=" + out, &output), 0)
      << output;
  EXPECT_THAT(output, HasSubstr("90 frames"));
  EXPECT_EQ(Read(out).num_frames(), 90);

  const std::string markers = testing::TempPath("walk.c3d");
  ASSERT_EQ(testing::RunCli("markers --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:1 "
                            "--noise_mm=1 --seed=3 --out=" + markers, &output), 0) << output;
  const std::string smooth = testing::TempPath("smooth.trc");
  const std::string report = testing::TempPath("filter.json");
  ASSERT_EQ(testing::RunCli("filter --markers=" + markers + " --levels=1 --out=" + smooth +
                            " --report=" + report, &output), 0) << output;
  MarkerTrajectories in, filtered;
  ASSERT_TRUE(ReadMarkerFile(markers, &in).ok());
  ASSERT_TRUE(ReadMarkerFile(smooth, &filtered).ok());
  EXPECT_EQ(filtered.num_frames(), in.num_frames());
  EXPECT_EQ(filtered.num_markers(), in.num_markers());
  std::ifstream json(report);
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("\"rms_change\""));
}

// --memory_mb: the pyramid's estimate (15 MB + 10.7 KB per frame) over the limit is refused
// with the figure, nothing written.
TEST_F(SignalCli, FilterRefusesOverMemoryLimit) {
  std::string output;
  const std::string out = testing::TempPath("limited.bvh");
  EXPECT_EQ(testing::RunCli("filter --motion=" + demo_ + " --levels=2 --memory_mb=10 --out=" + out, &output), 1);
  EXPECT_THAT(output, HasSubstr("--memory_mb=10: the pyramid filter on " + demo_ + " (90 frames) would need about 16 MB"));
  EXPECT_FALSE(testing::FileExists(out));
  EXPECT_EQ(testing::RunCli("filter --motion=" + demo_ + " --levels=2 --memory_mb=20 --out=" + out, &output), 0)
      << output;
}

TEST_F(SignalCli, BandsWithUnitWeightsKeepsTheMotion) {
  std::string output;
  const std::string out = testing::TempPath("same.bvh");
  ASSERT_EQ(
      testing::RunCli("bands --motion=" + demo_ + " --weights=1,1,1,1 --out=" + out, &output), 0)
      << output;
  EXPECT_LT(MaxRotationDifference(Read(demo_), Read(out)), 1e-4);  // BVH's 6 digits.
  const std::string edited = testing::TempPath("edited.bvh");
  ASSERT_EQ(testing::RunCli("bands --motion=" + demo_ + " --weights=2,1.5,0,1 --out=" + edited,
                            &output), 0) << output;
  EXPECT_GT(MaxRotationDifference(Read(demo_), Read(edited)), 1e-3);
}

TEST_F(SignalCli, BlendBothMethods) {
  std::string output;
  for (const char* method : {"multires", "weighted"}) {
    const std::string out = testing::TempPath(std::string(method) + ".bvh");
    ASSERT_EQ(testing::RunCli("blend --a=" + demo_ + " --b=" + demo_ + " --transition=30:40 "
                              "--b_start=0 --method=" + method + " --out=" + out, &output), 0)
        << output;
    EXPECT_THAT(output, HasSubstr("largest velocity jump"));
    EXPECT_LT(MaxRotationDifference(Read(demo_), Read(out)), 1e-4);  // Itself: the motion.
  }
  // Seconds, B from the transition start: 30 + 90 frames.
  const std::string later = testing::TempPath("later.bvh");
  ASSERT_EQ(testing::RunCli("blend --a=" + demo_ + " --b=" + demo_ +
                            " --transition=1s:1.5s --out=" + later, &output), 0) << output;
  EXPECT_EQ(Read(later).num_frames(), 120);
}

TEST_F(SignalCli, BadInputsFailWithOneLine) {
  std::string output;
  const std::string out = testing::TempPath("x.bvh");
  struct Case {
    std::string arguments, expected;
  };
  const Case cases[] = {
      {"filter --motion=" + demo_ + " --levels=9 --out=" + out, "levels"},
      {"filter --motion=" + demo_ + " --levels=2 --out=" + demo_, "overwrite"},
      {"filter --motion=/nonexistent.bvh --levels=2 --out=" + out, "/nonexistent.bvh"},
      {"filter --levels=2 --out=" + out, "--motion"},
      {"bands --motion=" + demo_ + " --weights=1,x,1 --out=" + out, "--weights"},
      {"bands --motion=" + demo_ + " --weights=1,1 --kernel_a=2 --out=" + out, "--kernel_a"},
      {"blend --a=" + demo_ + " --b=" + demo_ + " --transition=50:40 --out=" + out, "--transition"},
      {"blend --a=" + demo_ + " --b=" + demo_ + " --transition=5:8 --method=cubic --out=" + out,
       "--method"},
      {"blend --a=" + demo_ + " --b=" + demo_ + " --transition=abc --out=" + out, "--transition"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(testing::RunCli(c.arguments, &output), 1) << c.arguments << "\n" << output;
    EXPECT_THAT(output, HasSubstr(c.expected)) << c.arguments;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  }
  EXPECT_FALSE(testing::FileExists(out));
}

}  // namespace
}  // namespace mocapsolve
