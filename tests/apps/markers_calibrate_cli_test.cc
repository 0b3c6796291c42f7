// CLI smoke tests of `mocapsolve markers` and `mocapsolve calibrate`: synthesize markers
// from the demo clip with an auto marker set, calibrate them back, and compare with the
// set that made them; noise in mm; axes; bad flags give one-line errors.
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/bvh_reader.h"
#include "io/json_reader.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "kinematics/forward_kinematics.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

class MarkersCalibrateCli : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk.bvh");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=60 --fps=30", &output), 0) << output;
    ASSERT_TRUE(ReadBvh(demo_, &skeleton_, &motion_).ok());
  }

  // Markers of both sets agree on every frame of the demo clip (skeleton units, cm),
  // and each calibrated joint is the written one or an ancestor that moves with it
  // (the demo clip leaves some joints unanimated, so those cannot be told apart).
  void ExpectEquivalent(const std::string& written_path, const std::string& calibrated_path,
                        double tolerance_cm) {
    MarkerSet written, calibrated;
    Status status = ReadMarkerSet(written_path, skeleton_, &written);
    ASSERT_TRUE(status.ok()) << status.message();
    status = ReadMarkerSet(calibrated_path, skeleton_, &calibrated);
    ASSERT_TRUE(status.ok()) << status.message();
    ASSERT_EQ(calibrated.num_markers(), written.num_markers());
    int same_joint = 0;
    for (int m = 0; m < written.num_markers(); ++m) {
      const int c = calibrated.FindMarker(written.label(m));
      ASSERT_GE(c, 0) << written.label(m);
      const MarkerAttachment& w = written.marker(m).attachments[0];
      const MarkerAttachment& k = calibrated.marker(c).attachments[0];
      if (w.joint == k.joint) {
        ++same_joint;
        EXPECT_LT((w.offset - k.offset).norm(), tolerance_cm) << written.label(m);
      } else {
        EXPECT_TRUE(skeleton_.IsAncestorOrSelf(k.joint, w.joint)) << written.label(m);
      }
    }
    EXPECT_GE(same_joint, 2 * written.num_markers() / 3);
    FkData fk(skeleton_);
    double worst = 0.0;
    for (const Pose& pose : motion_.frames) {
      ForwardKinematics(skeleton_, pose, &fk);
      for (int m = 0; m < written.num_markers(); ++m) {
        const int c = calibrated.FindMarker(written.label(m));
        worst = std::max(worst, (written.Position(m, fk) - calibrated.Position(c, fk)).norm());
      }
    }
    EXPECT_LT(worst, tolerance_cm);
  }

  std::string demo_;
  Skeleton skeleton_;
  Motion motion_;
};

TEST_F(MarkersCalibrateCli, AutoMarkersToC3dAndTrcCalibrateBack) {
  std::string output;
  const std::string set = testing::TempPath("auto3.json");
  const std::string c3d = testing::TempPath("walk.c3d");
  const std::string trc = testing::TempPath("walk.trc");
  ASSERT_EQ(testing::RunCli("markers --quiet --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 "
                            "--write_markerset=" + set + " --out=" + c3d, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("60 frames at 30 fps (mm"));
  // TRC with the file in Z-up axes (x, y, z)_model = (x, z, -y)_file, and the same set.
  ASSERT_EQ(testing::RunCli("markers --quiet --motion=" + demo_ + " --skeleton_units=cm --markerset=" + set +
                            " --axes=x,z,-y --units=m --out=" + trc, &output), 0) << output;
  MarkerTrajectories from_c3d, from_trc;
  ASSERT_TRUE(ReadMarkerFile(c3d, &from_c3d).ok());
  ASSERT_TRUE(ReadMarkerFile(trc, &from_trc).ok());
  EXPECT_EQ(from_c3d.unit.name, "mm");
  EXPECT_EQ(from_trc.unit.name, "m");
  EXPECT_DOUBLE_EQ(from_c3d.frame_rate, 30.0);
  ASSERT_EQ(from_c3d.num_markers(), from_trc.num_markers());
  // Same marker, frame 10: the TRC is in metres and rotated.
  const Eigen::Vector3d a = from_c3d.position(10, 4), b = from_trc.position(10, 4);
  EXPECT_NEAR(a.x(), 1000.0 * b.x(), 1e-3);
  EXPECT_NEAR(a.y(), 1000.0 * b.z(), 1e-3);
  EXPECT_NEAR(a.z(), -1000.0 * b.y(), 1e-3);

  const std::string from_c3d_set = testing::TempPath("cal_c3d.json");
  const std::string report = testing::TempPath("cal_report.json");
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --skeleton_units=cm --markers=" + c3d +
                            " --attach=auto --out=" + from_c3d_set + " --report=" + report, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("axes x,y,z"));
  // C3D stores floats: ~1e-4 mm per coordinate at 1 m, so offsets agree to ~1e-5 cm.
  ExpectEquivalent(set, from_c3d_set, 1e-4);
  JsonNode json;
  ASSERT_TRUE(ReadJsonFile(report, &json).ok());
  ASSERT_NE(json.Find("rms_mm"), nullptr);
  EXPECT_LT(json.Find("rms_mm")->number, 1e-3);

  const std::string from_trc_set = testing::TempPath("cal_trc.json");
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --skeleton_units=cm --markers=" + trc +
                            " --attach=auto --axes=auto --out=" + from_trc_set, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("axes x,z,-y"));  // Found by the search.
  ExpectEquivalent(set, from_trc_set, 1e-6);  // TRC numbers round-trip as printed doubles.

  // Fixed attachments from the written set: offsets only.
  const std::string fixed_set = testing::TempPath("cal_fixed.json");
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --skeleton_units=cm --markers=" + trc +
                            " --axes=x,z,-y --attach=" + set + " --out=" + fixed_set, &output), 0) << output;
  MarkerSet written, fixed;
  ASSERT_TRUE(ReadMarkerSet(set, skeleton_, &written).ok());
  ASSERT_TRUE(ReadMarkerSet(fixed_set, skeleton_, &fixed).ok());
  ASSERT_EQ(fixed.num_markers(), written.num_markers());
  for (int m = 0; m < written.num_markers(); ++m) {
    EXPECT_EQ(fixed.marker(m).attachments[0].joint, written.marker(m).attachments[0].joint);
    EXPECT_LT((fixed.marker(m).attachments[0].offset - written.marker(m).attachments[0].offset).norm(), 1e-6);
  }
}

// --out_subject alone is enough (the subject holds the marker set), and the subject
// holds its skeleton inline: copied into another folder, without the BVH it was
// calibrated on, it still solves the take.
TEST_F(MarkersCalibrateCli, SubjectAloneAndCopiedElsewhere) {
  std::string output;
  const std::string c3d = testing::TempPath("subject_walk.c3d");
  ASSERT_EQ(testing::RunCli("markers --quiet --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 --out=" +
                            c3d, &output), 0) << output;
  const std::string subject = testing::TempPath("calibrated/S.json"), report = testing::TempPath("subject_cal.json");
  std::filesystem::create_directories(testing::TempPath("calibrated"));
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --skeleton_units=cm --markers=" + c3d +
                            " --out_subject=" + subject + " --report=" + report, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("wrote subject " + subject));
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"out\": \"\""));
  const std::string text = testing::ReadTextFile(subject);
  EXPECT_THAT(text, HasSubstr("\"skeleton\": {"));
  EXPECT_EQ(text.find("walk.bvh"), std::string::npos);

  const std::string copy = testing::TempPath("elsewhere/deeper/S.json");
  std::filesystem::create_directories(testing::TempPath("elsewhere/deeper"));
  std::filesystem::copy_file(subject, copy, std::filesystem::copy_options::overwrite_existing);
  const std::string solved = testing::TempPath("elsewhere/solved.bvh");
  ASSERT_EQ(testing::RunCli("solve --quiet --subject=" + copy + " --markers=" + c3d + " --out=" + solved, &output), 0)
      << output;
  EXPECT_TRUE(testing::FileExists(solved));

  // Neither output: one line, exit 1.
  EXPECT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --skeleton_units=cm --markers=" + c3d, &output), 1);
  EXPECT_EQ(output, "mocapsolve calibrate: --out=SET.json and/or --out_subject=S.json is required\n");
}

TEST_F(MarkersCalibrateCli, NoiseIsInMillimetresAndSeeded) {
  std::string output;
  const std::string trc_a = testing::TempPath("noisy_a.trc"), trc_b = testing::TempPath("noisy_b.trc");
  for (const std::string& out : {trc_a, trc_b}) {
    ASSERT_EQ(testing::RunCli("markers --quiet --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 "
                              "--noise_mm=2 --seed=5 --units=cm --out=" + out, &output), 0) << output;
  }
  const std::string text_a = testing::ReadTextFile(trc_a);
  EXPECT_EQ(text_a.substr(text_a.find('\n')), testing::ReadTextFile(trc_b).substr(testing::ReadTextFile(trc_b).find('\n')));  // Same seed.
  const std::string report = testing::TempPath("noisy.json");
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --skeleton_units=cm --markers=" + trc_a +
                            " --out=" + testing::TempPath("noisy_set.json") + " --report=" + report, &output), 0)
      << output;
  JsonNode json;
  ASSERT_TRUE(ReadJsonFile(report, &json).ok());
  // sigma = 2 mm per coordinate in a cm file: the residual RMS about each fitted offset
  // is sigma * sqrt(3 (1 - 1/60)) = 3.43 mm (auto attach may fit a little of the noise).
  const double rms_mm = json.Find("rms_mm")->number;
  EXPECT_GT(rms_mm, 3.1);
  EXPECT_LT(rms_mm, 3.7);
}

TEST_F(MarkersCalibrateCli, BadFlagsAndInputsGiveOneLineErrors) {
  std::string output;
  const auto one_line = [](const std::string& text) {
    return std::count(text.begin(), text.end(), '\n') == 1;
  };
  const std::string out = testing::TempPath("x.c3d");
  EXPECT_EQ(testing::RunCli("markers --quiet --motion=" + demo_ + " --markerset=auto:0 --out=" + out, &output), 1);
  EXPECT_TRUE(one_line(output)) << output;
  EXPECT_THAT(output, HasSubstr("auto:N"));
  EXPECT_EQ(testing::RunCli("markers --quiet --motion=" + demo_ + " --markerset=auto:3 --out=" +
                            testing::TempPath("x.trc"), &output), 1);  // BVH has no unit; TRC needs one.
  EXPECT_THAT(output, HasSubstr("--skeleton_units"));
  EXPECT_EQ(testing::RunCli("markers --quiet --motion=" + demo_ + " --markerset=auto:3 --out=" + demo_, &output), 1);
  EXPECT_THAT(output, HasSubstr(".c3d or .trc"));
  EXPECT_EQ(testing::RunCli("markers --quiet --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 --out=" +
                            out + " --write_markerset=" + demo_ + ".json --units=furlong", &output), 1);
  EXPECT_THAT(output, HasSubstr("furlong"));
  EXPECT_FALSE(testing::FileExists(out));
  EXPECT_FALSE(testing::FileExists(demo_ + ".json"));

  EXPECT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --out=" + testing::TempPath("c.json"), &output), 1);
  EXPECT_THAT(output, HasSubstr("--markers"));
  ASSERT_EQ(testing::RunCli("markers --quiet --motion=" + demo_ + " --markerset=auto:2 --out=" + out, &output), 0)
      << output;  // Unknown unit: written in skeleton units with a warning (quiet here).
  EXPECT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --markers=" + out + " --out=" + out, &output), 1);
  EXPECT_THAT(output, HasSubstr("expected a .json"));
  EXPECT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --markers=" + out + " --out=" +
                            testing::TempPath("c.json"), &output), 1);  // Units unknown on both sides.
  EXPECT_TRUE(one_line(output)) << output;
  EXPECT_THAT(output, HasSubstr("--marker_scale"));
  EXPECT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --markers=" + out + " --marker_scale=1 "
                            "--axes=x,y,y --out=" + testing::TempPath("c.json"), &output), 1);
  EXPECT_THAT(output, HasSubstr("x,y,y"));
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --markers=" + out + " --marker_scale=1 "
                            "--out=" + testing::TempPath("c.json"), &output), 0) << output;
  EXPECT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --markers=" + out + " --marker_scale=1 "
                            "--frame_offset=100 --out=" + testing::TempPath("d.json"), &output), 1);
  EXPECT_THAT(output, HasSubstr("no overlapping frames"));
  EXPECT_FALSE(testing::FileExists(testing::TempPath("d.json")));
  EXPECT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --markers=" + out + " --marker_scale=1 "
                            "--attach=/nonexistent/set.json --out=" + testing::TempPath("d.json"), &output), 1);
  EXPECT_THAT(output, HasSubstr("/nonexistent/set.json"));

  EXPECT_EQ(testing::RunCli("--help", &output), 0);
  EXPECT_THAT(output, HasSubstr("markers"));
  EXPECT_THAT(output, HasSubstr("calibrate"));
  EXPECT_EQ(testing::RunCli("calibrate --help", &output), 0);
  EXPECT_THAT(output, HasSubstr("--attach"));
  EXPECT_THAT(output, HasSubstr("y,z,x"));
  EXPECT_EQ(testing::RunCli("markers --help", &output), 0);
  EXPECT_THAT(output, HasSubstr("--noise_mm"));
}

}  // namespace
}  // namespace mocapsolve
