// `mocapsolve label` end to end on the demo walk's synthetic markers (their labels are
// ignored: every point is a candidate), and the bad inputs the command must refuse with
// exit 1, one line and nothing written: points 10 times too large for the subject (the
// best match named), a take of 0 frames.
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/marker_file.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

class LabelCli : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk.bvh");
    markers_ = testing::TempPath("walk.c3d");
    set_ = testing::TempPath("set.json");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=60 --fps=60", &output), 0) << output;
    ASSERT_EQ(testing::RunCli("markers --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 "
                              "--write_markerset=" + set_ + " --out=" + markers_, &output), 0) << output;
  }
  int Label(const std::string& extra, std::string* output) {
    return testing::RunCli("label --skeleton=" + demo_ + " --skeleton_units=cm --markerset=" + set_ +
                               " --markers=" + markers_ + " " + extra, output);
  }
  std::string demo_, markers_, set_;
};

TEST_F(LabelCli, GivesThePointsTheirLabels) {
  const std::string out = testing::TempPath("labelled.c3d");
  std::string output;
  ASSERT_EQ(Label("--out=" + out + " --report=" + testing::TempPath("label.json"), &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("swaps avoided"));
  MarkerTrajectories input, labelled;
  ASSERT_TRUE(ReadMarkerFile(markers_, &input).ok());
  ASSERT_TRUE(ReadMarkerFile(out, &labelled).ok());
  ASSERT_EQ(labelled.num_frames(), input.num_frames());
  int correct = 0, wrong = 0, samples = 0;
  for (int c = 0; c < input.num_markers(); ++c) {
    const int m = labelled.FindMarker(input.label(c));
    ASSERT_GE(m, 0) << input.label(c);
    for (int f = 0; f < input.num_frames(); ++f) {
      samples += input.valid(f, c);
      if (!labelled.valid(f, m)) continue;
      // The file's own sample, bit for bit, under its label.
      if (input.valid(f, c) && (input.position(f, c) - labelled.position(f, m)).norm() == 0.0) ++correct;
      else ++wrong;
    }
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(correct, 0.95 * samples) << correct << " of " << samples;
}

TEST_F(LabelCli, RefusesPointsTenTimesTooLarge) {
  const std::string out = testing::TempPath("x10.c3d");
  std::string output;
  EXPECT_EQ(Label("--quiet --marker_scale=10 --acquire_frames=2 --out=" + out, &output), 1);
  EXPECT_THAT(output, HasSubstr("best match"));
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace mocapsolve
