// Numerical faults (issue 15, item 5), end to end through the commands: each gives a
// clear one-line error or the documented behaviour below, and never a NaN or an infinity
// in an output file.
//   - Frames whose markers are all missing: the per-frame solve keeps the previous
//     frame's pose there and counts them as unsolved; the whole-clip solve carries the
//     smoothness term across them; repair fills them from the reference.
//   - Markers that coincide (two labels on one point): solved and repaired as any other
//     marker; nothing is flagged.
//   - Zero-length bones: marker sets, solves and calibration work (a bone's direction is
//     never normalized from its length).
//   - A clip of identical frames: the Green's function and harmonic falloffs have no
//     automatic width (the median pose step is 0) and say so, asking for --sigma; with it,
//     or with the spline falloff, the result is finite.
// (Skin weights that do not sum to 1 are renormalized per vertex, and weights that name a
// joint outside the skin are an error: tests/kinematics/skinning_test.cc and the annotated
// bad glTF files.)
#include <algorithm>
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

// True if a text output holds a NaN or an infinity as a number.
bool HasNonFinite(const std::string& text) {
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* word : {"nan", "inf"}) {
    for (size_t at = lower.find(word); at != std::string::npos; at = lower.find(word, at + 1)) {
      const bool letter_before = at > 0 && std::isalpha(static_cast<unsigned char>(lower[at - 1]));
      const size_t end = at + 3;
      const bool letter_after = end < lower.size() && std::isalpha(static_cast<unsigned char>(lower[end])) &&
                                lower.compare(at, 8, "infinity") != 0;
      if (!letter_before && !letter_after) return true;
    }
  }
  return false;
}

void ExpectFiniteFile(const std::string& path) {
  const std::string text = testing::ReadTextFile(path);
  ASSERT_FALSE(text.empty()) << path;
  EXPECT_FALSE(HasNonFinite(text)) << path;
}

void Replace(std::string* text, const std::string& from, const std::string& to) {
  const size_t at = text->find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text->replace(at, from.size(), to);
}


class NumericalFaults : public ::testing::Test {
 protected:
  void SetUp() override {
    walk_ = testing::TempPath("walk.bvh");
    set_ = testing::TempPath("set.json");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + walk_ + " --frames=40 --fps=30", &output), 0) << output;
    ASSERT_EQ(testing::RunCli("markers --motion=" + walk_ + " --skeleton_units=cm --markerset=auto:3 "
                              "--write_markerset=" + set_ + " --out=" + testing::TempPath("walk.trc"), &output), 0)
        << output;
  }
  int Run(const std::string& arguments) {
    output_.clear();
    return testing::RunCli(arguments, &output_);
  }
  std::string walk_, set_, output_;
};

TEST_F(NumericalFaults, FramesWithEveryMarkerMissing) {
  // Blank frames 5-7 of the TRC: every coordinate column empty.
  std::istringstream in(testing::ReadTextFile(testing::TempPath("walk.trc")));
  std::string text, line;
  for (int row = 0; std::getline(in, line); ++row) {
    if (row >= 5) {
      const size_t tab1 = line.find('\t'), tab2 = line.find('\t', tab1 + 1);
      const int frame = std::atoi(line.substr(0, tab1).c_str());
      if (frame >= 6 && frame <= 8) {  // TRC frames count from 1.
        const int columns = static_cast<int>(std::count(line.begin(), line.end(), '\t')) - 1;
        line = line.substr(0, tab2) + std::string(columns, '\t');
      }
    }
    text += line + "\n";
  }
  const std::string markers = testing::TempPath("holes.trc");
  testing::WriteTextFile(markers, text);
  const std::string solve = "solve --skeleton=" + walk_ + " --skeleton_units=cm --markers=" + markers +
                            " --markerset=" + set_;
  for (const std::string solver : {"dls", "ceres"}) {
    const std::string out = testing::TempPath("frame_" + solver + ".bvh"), report = out + ".json";
    ASSERT_EQ(Run(solve + " --solver=" + solver + " --out=" + out + " --report=" + report), 0) << output_;
    ExpectFiniteFile(out);
    ExpectFiniteFile(report);
    EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"unsolved_frames\": 3")) << solver;
  }
  for (const std::string clip_solver : {"ceres", "dls"}) {
    const std::string clip = testing::TempPath("clip_" + clip_solver + ".bvh");
    ASSERT_EQ(Run(solve + " --mode=clip --clip_solver=" + clip_solver + " --out=" + clip), 0) << output_;
    EXPECT_THAT(output_, HasSubstr("clip (" + clip_solver + ")"));
    ExpectFiniteFile(clip);
  }
  const std::string refused = testing::TempPath("clip_refused.bvh");
  EXPECT_EQ(Run(solve + " --mode=clip --clip_solver=newton --out=" + refused), 1);
  EXPECT_THAT(output_, HasSubstr("--clip_solver: unknown 'newton' (ceres, dls)"));
  EXPECT_FALSE(testing::FileExists(refused));
  const std::string repaired = testing::TempPath("repaired.trc"), repaired_motion = testing::TempPath("repaired.bvh");
  ASSERT_EQ(Run("repair --skeleton=" + walk_ + " --skeleton_units=cm --markers=" + markers + " --markerset=" + set_ +
                " --out_markers=" + repaired + " --out_motion=" + repaired_motion),
            0) << output_;
  ExpectFiniteFile(repaired);
  ExpectFiniteFile(repaired_motion);
  // The blank frames are filled: no empty coordinate in the repaired file's rows.
  std::istringstream rows(testing::ReadTextFile(repaired));
  int row = 0;
  for (std::string line; std::getline(rows, line); ++row) {
    if (row >= 5) {
      EXPECT_EQ(line.find("\t\t"), std::string::npos) << "row " << row;
    }
  }
  EXPECT_GT(row, 40);
}

TEST_F(NumericalFaults, MarkersThatCoincide) {
  // Twin labels on the same attachment as Hips_0 and LeftForeArm_1.
  std::string set = testing::ReadTextFile(set_);
  for (const std::string label : {"Hips_0", "LeftForeArm_1"}) {
    const size_t begin = set.find("{\"label\": \"" + label + "\"");
    ASSERT_NE(begin, std::string::npos) << label;
    const size_t end = set.find('\n', begin);
    std::string twin = set.substr(begin, end - begin);
    if (twin.back() != ',') twin += ',';
    Replace(&twin, "\"" + label + "\"", "\"" + label + "_twin\"");
    set.insert(begin, twin + "\n    ");
  }
  const std::string twin_set = testing::TempPath("twins.json"), markers = testing::TempPath("twins.c3d");
  testing::WriteTextFile(twin_set, set);
  ASSERT_EQ(Run("markers --motion=" + walk_ + " --skeleton_units=cm --markerset=" + twin_set + " --out=" + markers), 0)
      << output_;
  const std::string solved = testing::TempPath("twins.bvh");
  ASSERT_EQ(Run("solve --skeleton=" + walk_ + " --skeleton_units=cm --markers=" + markers + " --markerset=" +
                twin_set + " --out=" + solved),
            0) << output_;
  ExpectFiniteFile(solved);
  const std::string repaired = testing::TempPath("twins_repaired.trc"), report = testing::TempPath("twins.json.r");
  ASSERT_EQ(Run("repair --skeleton=" + walk_ + " --skeleton_units=cm --markers=" + markers + " --markerset=" +
                twin_set + " --out_markers=" + repaired + " --report=" + report),
            0) << output_;
  ExpectFiniteFile(repaired);
  EXPECT_THAT(output_, HasSubstr("0 intervals detected"));
}

TEST_F(NumericalFaults, ZeroLengthBones) {
  std::string bvh = testing::ReadTextFile(walk_);
  Replace(&bvh, "OFFSET 28 0 0", "OFFSET 0 0 0");  // LeftForeArm onto LeftArm.
  Replace(&bvh, "OFFSET 0 15 0", "OFFSET 0 0 0");  // The first spine segment.
  const std::string zero = testing::TempPath("zero.bvh"), set = testing::TempPath("zero_set.json"),
                    markers = testing::TempPath("zero.c3d");
  testing::WriteTextFile(zero, bvh);
  ASSERT_EQ(Run("markers --motion=" + zero + " --skeleton_units=cm --markerset=auto:3 --write_markerset=" + set +
                " --out=" + markers),
            0) << output_;
  ExpectFiniteFile(set);
  for (const std::string solver : {"dls", "ceres"}) {
    const std::string solved = testing::TempPath("zero_" + solver + ".bvh");
    ASSERT_EQ(Run("solve --skeleton=" + zero + " --skeleton_units=cm --markers=" + markers + " --markerset=" + set +
                  " --solver=" + solver + " --out=" + solved),
              0) << output_;
    ExpectFiniteFile(solved);
  }
  const std::string calibrated = testing::TempPath("zero_calibrated.json"),
                    subject = testing::TempPath("zero_subject.json");
  ASSERT_EQ(Run("calibrate --motion=" + zero + " --skeleton_units=cm --markers=" + markers +
                " --attach=auto --out=" + calibrated + " --out_subject=" + subject),
            0) << output_;
  ExpectFiniteFile(calibrated);
  ExpectFiniteFile(subject);
}

TEST_F(NumericalFaults, ClipOfIdenticalFrames) {
  std::string bvh = testing::ReadTextFile(walk_);
  const size_t motion = bvh.find("Frame Time:");
  ASSERT_NE(motion, std::string::npos);
  const size_t first = bvh.find('\n', motion) + 1;
  const std::string frame = bvh.substr(first, bvh.find('\n', first) + 1 - first);
  std::string still = bvh.substr(0, first);
  for (int f = 0; f < 40; ++f) still += frame;
  const std::string clip = testing::TempPath("still.bvh");
  testing::WriteTextFile(clip, still);
  for (const std::string method : {"green", "diffusion"}) {
    EXPECT_EQ(Run("distance --motion=" + clip + " --frame=10 --method=" + method + " --out=" +
                  testing::TempPath("no.csv")),
              1) << method;
    EXPECT_THAT(output_, HasSubstr("sigma"));
    EXPECT_EQ(std::count(output_.begin(), output_.end(), '\n'), 1) << output_;
    EXPECT_FALSE(testing::FileExists(testing::TempPath("no.csv")));
  }
  const std::string falloff = testing::TempPath("falloff.csv");
  ASSERT_EQ(Run("distance --motion=" + clip + " --frame=10 --method=green --sigma=1 --out=" + falloff), 0) << output_;
  ExpectFiniteFile(falloff);
  const std::string edit = testing::TempPath("edit.json");
  testing::WriteTextFile(edit, "{\"frame\": 10, \"joints\": {\"LeftArm\": {\"rotation_offset_deg\": [0, 0, 30]}}}\n");
  for (const std::string method : {"green", "harmonic"}) {
    EXPECT_EQ(Run("propagate --motion=" + clip + " --edit=" + edit + " --method=" + method + " --out=" +
                  testing::TempPath("no.bvh")),
              1) << method;
    EXPECT_THAT(output_, HasSubstr("sigma"));
    EXPECT_FALSE(testing::FileExists(testing::TempPath("no.bvh")));
  }
  const std::string edited = testing::TempPath("edited.bvh");
  ASSERT_EQ(Run("propagate --motion=" + clip + " --edit=" + edit + " --method=spline --out=" + edited), 0) << output_;
  ExpectFiniteFile(edited);
}

}  // namespace
}  // namespace mocapsolve
