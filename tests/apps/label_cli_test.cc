// `mocapsolve label` end to end on the demo walk's synthetic markers (their labels are
// ignored: every point is a candidate), and the bad inputs the command must refuse with
// exit 1, one line and nothing written: points 10 times too large for the subject (the
// best match named), a take of 0 frames.
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/marker_file.h"
#include "pipeline/subject.h"
#include "problems/marker_label/label_fixture.h"
#include "tasks/label_task.h"
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

// Real data, as a studio works: CMU subject 2 calibrated once on 02_01, then another take
// (cmu_02_05) stripped of its labels and shuffled every frame. LFIN (thumb) and LWRA (hand)
// are each the only marker of their joint and fit either way round within ~1 %: the
// tracks must keep them apart (no wrong sample; once, the periodic check exchanged them
// for 1,257 frames).
TEST(LabelRealData, CrossTakeSubjectKeepsEveryTrack) {
  MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
  MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
  MOCAPSOLVE_DATA_FILE(calibration, "c3d/02_01.c3d");
  MOCAPSOLVE_DATA_FILE(take, "c3d/cmu_02_05.c3d");
  const std::string subject_path = testing::TempPath("S02_label.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + amc + " --skeleton=" + asf + " --markers=" + calibration +
                                " --axes=y,z,x --out=" + testing::TempPath("02_label.json") +
                                " --out_subject=" + subject_path,
                            &output),
            0)
      << output;
  Subject subject;
  ASSERT_TRUE(ReadSubject(subject_path, &subject).ok());
  MarkerTrajectories labelled;
  ASSERT_TRUE(ReadMarkerFile(take, &labelled).ok());
  ScrambleOptions scramble;
  scramble.seed = 5;
  const ScrambledTake raw = ScrambleLabels(labelled, scramble);
  LabelResult result;
  ASSERT_TRUE(RunLabel(subject, raw.points, "cmu_02_05 (scrambled)", LabelConfig(), nullptr, &result).ok());
  std::vector<std::vector<std::string>> labels(raw.truth.size());
  for (size_t f = 0; f < labels.size(); ++f) {
    labels[f].assign(raw.truth[f].size(), "");
    for (size_t c = 0; c < labels[f].size(); ++c) {
      const int m = result.marker_of_sample[f][c];
      if (m >= 0) labels[f][c] = subject.markers.label(m);
    }
  }
  std::vector<std::string> scored;
  for (int m = 0; m < subject.markers.num_markers(); ++m) scored.push_back(subject.markers.label(m));
  const LabelScore score = ScoreLabels(raw.truth, labels, scored);
  EXPECT_EQ(score.wrong, 0) << "longest wrong run " << score.longest_wrong_run;
  EXPECT_GE(score.accuracy(), 0.999) << score.correct << " of " << score.truth_samples;
}

}  // namespace
}  // namespace mocapsolve
