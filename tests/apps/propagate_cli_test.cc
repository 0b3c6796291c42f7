// `mocapsolve propagate`: the three falloffs and --keep_contacts on CMU 16_15, an IK edit
// through both solvers, and bad inputs (including the annotated bad edit files) that
// must fail with one line.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/json_reader.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

class PropagateCli : public ::testing::Test {
 protected:
  void SetUp() override {
    edit_ = testing::TempPath("hips.json");
    std::ofstream(edit_) << R"({"frame": 200, "joints": {"root": {"rotation_offset_deg": [10, 0, 0]}},
                               "root_translation_offset": [0, -6, 0]})";
  }
  std::string edit_;
};

double ReportNumber(const std::string& path, const std::string& section, const std::string& key) {
  JsonNode root;
  if (!ReadJsonFile(path, &root).ok()) return NAN;
  const JsonNode* object = root.Find(section);
  const JsonNode* value = object == nullptr ? nullptr : object->Find(key);
  return value != nullptr && value->is_number() ? value->number : NAN;
}

TEST_F(PropagateCli, FalloffsAndKeepContactsOn16_15) {
  MOCAPSOLVE_DATA_FILE(motion, "bvh/16_15.bvh");
  Skeleton skeleton;
  Motion source;
  ASSERT_TRUE(ReadMotionFile(motion, MotionFileOptions(), &skeleton, &source).ok());
  for (const char* method : {"green", "harmonic", "spline"}) {
    SCOPED_TRACE(method);
    const std::string out = testing::TempPath(std::string(method) + ".bvh");
    const std::string report = testing::TempPath(std::string(method) + ".json");
    const std::string csv = testing::TempPath(std::string(method) + ".csv");
    std::string output;
    ASSERT_EQ(testing::RunCli("propagate --motion=" + motion + " --skeleton_units=cm --edit=" + edit_ +
                              " --method=" + method + " --keep_contacts --out=" + out +
                              " --weights_csv=" + csv + " --report=" + report, &output), 0)
        << output;
    EXPECT_THAT(output, HasSubstr("wrote " + out));
    // Without the re-solve the planted feet skate by several cm; with it, under 1 cm.
    EXPECT_GT(ReportNumber(report, "contacts", "max_drift_cm_without_keep"), 3.0);
    EXPECT_LT(ReportNumber(report, "contacts", "max_drift_cm_with_keep"), 1.0);
    Skeleton out_skeleton;
    Motion edited;
    ASSERT_TRUE(ReadMotionFile(out, MotionFileOptions(), &out_skeleton, &edited).ok());
    ASSERT_EQ(edited.num_frames(), source.num_frames());
    // The edited frame got the whole edit: root 6 cm lower (BVH text keeps 6 digits).
    EXPECT_NEAR(edited.frames[200].translations[0].y(), source.frames[200].translations[0].y() - 6.0, 1e-3);
    EXPECT_NEAR(AngularDistance(edited.frames[200].rotations[0], source.frames[200].rotations[0]),
                DegToRad(10.0), 1e-4);
    const std::string weights = testing::ReadTextFile(csv);
    EXPECT_EQ(weights.rfind("frame,weight\n0,", 0), 0u);
    EXPECT_THAT(weights, HasSubstr("\n200,1\n"));
  }
}

TEST_F(PropagateCli, HarmonicFollowsTheGreensFalloffOn16_15) {
  MOCAPSOLVE_DATA_FILE(motion, "bvh/16_15.bvh");
  const std::string report = testing::TempPath("compare.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("propagate --motion=" + motion + " --skeleton_units=cm --edit=" + edit_ +
                            " --method=harmonic --compare_falloffs --out=" + testing::TempPath("h.bvh") +
                            " --report=" + report, &output), 0) << output;
  JsonNode root;
  ASSERT_TRUE(ReadJsonFile(report, &root).ok());
  const JsonNode* green = root.Find("comparison")->Find("green");
  ASSERT_NE(green, nullptr);
  // Measured 0.94 / 0.33 with the default ground weight (0.31 / 0.68 without it).
  EXPECT_GT(green->Find("correlation")->number, 0.85);
  EXPECT_LT(green->Find("max_difference")->number, 0.45);
  EXPECT_THAT(output, HasSubstr("harmonic vs green falloff of frame 200"));
}

TEST_F(PropagateCli, IkTargetWithBothSolvers) {
  MOCAPSOLVE_DATA_FILE(motion, "bvh/16_15.bvh");
  Skeleton skeleton;
  Motion source;
  ASSERT_TRUE(ReadMotionFile(motion, MotionFileOptions(), &skeleton, &source).ok());
  FkData fk(skeleton);
  ForwardKinematics(skeleton, source.frames[200], &fk);
  const int wrist = skeleton.FindJoint("lwrist");
  ASSERT_GE(wrist, 0);
  const Eigen::Vector3d target = fk.world_positions[wrist] + Eigen::Vector3d(0.0, 20.0, 10.0);
  char spec[128];
  std::snprintf(spec, sizeof spec, "lwrist:%.6f,%.6f,%.6f", target.x(), target.y(), target.z());
  for (const char* solver : {"ceres", "dls"}) {
    SCOPED_TRACE(solver);
    const std::string out = testing::TempPath(std::string("ik_") + solver + ".bvh");
    const std::string report = testing::TempPath(std::string("ik_") + solver + ".json");
    std::string output;
    ASSERT_EQ(testing::RunCli("propagate --motion=" + motion + " --skeleton_units=cm --frame=200 "
                              "--ik_target=" + std::string(spec) + " --solver=" + solver +
                              " --method=spline --out=" + out + " --report=" + report, &output), 0)
        << output;
    // The default prior (2 cm per radian) leaves a sub-millimetre bias at the target.
    EXPECT_LT(ReportNumber(report, "edit", "ik_max_target_error"), 0.1);
    Skeleton out_skeleton;
    Motion edited;
    ASSERT_TRUE(ReadMotionFile(out, MotionFileOptions(), &out_skeleton, &edited).ok());
    ForwardKinematics(out_skeleton, edited.frames[200], &fk);
    EXPECT_LT((fk.world_positions[wrist] - target).norm(), 0.1);  // cm, after BVH rounding.
  }
}

TEST_F(PropagateCli, BadInputsFailWithOneLine) {
  MOCAPSOLVE_DATA_FILE(motion, "bvh/16_15.bvh");
  const std::string out = testing::TempPath("bad.bvh");
  const std::string base = "propagate --motion=" + motion + " --skeleton_units=cm --out=" + out;
  const struct {
    std::string arguments;
    const char* expected;
  } cases[] = {
      {base, "give exactly one of --edit"},
      {base + " --edit=" + edit_ + " --ik_target=lwrist:0,0,0", "give exactly one of --edit"},
      {base + " --edit=" + edit_ + " --method=multires", "--method: unknown 'multires' (green, harmonic, spline)"},
      {base + " --edit=" + edit_ + " --frame=12", "but --frame=12"},
      {base + " --edit=" + edit_ + " --region=0:100", "--region: edited frame 200 lies outside 0:100"},
      {base + " --frame=10 --ik_target=nose:0,0,0", "--ik_target: unknown joint 'nose'"},
      {base + " --frame=10 --ik_target=lwrist:0,0", "--ik_target: expected JOINT:x,y,z"},
      {base + " --frame=9999 --ik_target=lwrist:0,0,0", "--frame: expected 0 <= frame < 471"},
      {base + " --edit=" + edit_ + " --method=spline --spline_width=0", "--spline_width must be positive"},
      {base + " --edit=" + edit_ + " --keep_contacts --foot_joints=hand", "--foot_joints: unknown joint"},
      // The Green's function over 471 frames: 16.5 MB + 4.7 KB per frame.
      {base + " --edit=" + edit_ + " --memory_mb=10", "--memory_mb=10: the Green's function on the motion (471 frames) "
                                                      "would need about 19 MB"},
      {base + " --edit=/nonexistent/edit.json", "/nonexistent/edit.json"},
  };
  for (const auto& c : cases) {
    std::string output;
    EXPECT_EQ(testing::RunCli(c.arguments, &output), 1) << c.arguments;
    EXPECT_THAT(output, HasSubstr(c.expected)) << c.arguments;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
    EXPECT_FALSE(testing::FileExists(out)) << c.arguments;
  }
  // The annotated bad edit files (see edit_file_test.cc): same one-line message.
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testing::SourcePath("tests/data/bad"))) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("bad_edit_", 0) != 0) continue;
    const std::string file = entry.path().string();
    JsonNode root;
    ASSERT_TRUE(ReadJsonFile(file, &root).ok());
    const std::string comment = root.Find("comment")->string;
    const std::string expected = file + ":" + comment.substr(std::string("expect-error: ").size());
    std::string output;
    EXPECT_EQ(testing::RunCli(base + " --edit=" + file, &output), 1) << file;
    EXPECT_THAT(output, HasSubstr(expected));
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
    EXPECT_FALSE(testing::FileExists(out));
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

}  // namespace
}  // namespace mocapsolve
