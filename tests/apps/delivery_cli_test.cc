// The delivery options (settings/delivery_settings.h: --frames=A:B, --seconds=A:B,
// --out_fps) on convert, retarget and pipeline, every output format: the written clip is
// the cut, resampled one (its frames the source's at the output times), the added glTF
// clip is the file's first; a malformed or out-of-range value is one line naming the
// option, exit 1, nothing written. Fixtures: the demo walk and the test humanoid.
#include <algorithm>
#include <cstdio>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/bvh_reader.h"
#include "io/fbx_reader.h"
#include "io/gltf_reader.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
#include "tests/gltf_test_files.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

// The largest distance between joint `name`'s world positions in `b`'s frames and in
// `a`'s frames first_a, first_a + step_a, ...
double LargestDistance(const Skeleton& a, const Motion& ma, int first_a, int step_a, const Skeleton& b,
                       const Motion& mb) {
  FkData fa(a), fb(b);
  double worst = 0.0;
  int compared = 0;
  for (int k = 0; k < mb.num_frames(); ++k) {
    const int f = first_a + step_a * k;
    if (f >= ma.num_frames()) {
      ADD_FAILURE() << "frame " << k << " is past the source's end";
      break;
    }
    ForwardKinematics(a, ma.frames[f], &fa);
    ForwardKinematics(b, mb.frames[k], &fb);
    for (int j = 0; j < b.num_joints(); ++j) {
      const int i = a.FindJoint(b.name(j));
      if (i < 0) continue;
      worst = std::max(worst, (fa.world_positions[i] - fb.world_positions[j]).norm());
      ++compared;
    }
  }
  EXPECT_GT(compared, 0);
  return worst;
}

class DeliveryCli : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk120.bvh");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=121 --fps=120", &output), 0) << output;
    ASSERT_TRUE(ReadBvh(demo_, &skeleton_, &motion_).ok());
  }
  std::string demo_;
  Skeleton skeleton_;
  Motion motion_;
};

TEST_F(DeliveryCli, ConvertCutsAndResamplesEveryFormat) {
  std::string output;
  // BVH: frames 20..100 at 30 fps are the source's frames 20, 24, ..., 100.
  const std::string bvh = testing::TempPath("cut.bvh");
  ASSERT_EQ(testing::RunCli("convert " + demo_ + " " + bvh + " --frames=20:100 --out_fps=30 --precision=9", &output),
            0) << output;
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadBvh(bvh, &skeleton, &motion).ok());
  EXPECT_EQ(motion.num_frames(), 21);
  EXPECT_NEAR(motion.frame_rate, 30.0, 1e-6);
  EXPECT_LT(LargestDistance(skeleton_, motion_, 20, 4, skeleton, motion), 1e-5);  // cm, 9 digits.
  // FBX, by seconds: 0.5 s .. the end at 60 fps: frames 60, 62, ..., 120.
  const std::string fbx = testing::TempPath("cut.fbx");
  ASSERT_EQ(testing::RunCli("convert " + demo_ + " " + fbx + " --seconds=0.5: --out_fps=60", &output), 0) << output;
  Status status = ReadMotionFile(fbx, {}, &skeleton, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(motion.num_frames(), 31);
  EXPECT_NEAR(motion.frame_rate, 60.0, 1e-6);
  EXPECT_LT(LargestDistance(skeleton_, motion_, 60, 2, skeleton, motion), 1e-3);  // cm: float keys.
  // Bad values: one line naming the option, nothing written.
  for (const std::string bad : {"--frames=20:121", "--frames=20-30", "--seconds=0.5:2", "--out_fps=-30",
                                 "--frames=1:2 --seconds=0:1"}) {
    const std::string none = testing::TempPath("none.bvh");
    EXPECT_EQ(testing::RunCli("convert " + demo_ + " " + none + " " + bad, &output), 1) << bad;
    EXPECT_THAT(output, HasSubstr(bad.substr(0, bad.find_first_of("=")))) << output;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
    EXPECT_FALSE(testing::FileExists(none)) << bad;
  }
  EXPECT_THAT(output, HasSubstr("--frames and --seconds: give one range, not both"));
  testing::RunCli("convert " + demo_ + " x.bvh --frames=20:121", &output);
  EXPECT_THAT(output, HasSubstr("--frames=20:121: the clip has 121 frames, 0:120"));
}

// The take on the test humanoid: retarget's --out (glTF, FBX) and --out_bvh hold the
// delivered clip; pipeline's character files too, with the take the glTF's first clip.
TEST_F(DeliveryCli, RetargetAndPipelineDeliverTheCutResampledTake) {
  const std::string character = testing::TempPath("figure.gltf");
  testing::WriteTestCharacter(character, 45.0);
  std::string output;
  const std::string full = testing::TempPath("full.bvh");
  ASSERT_EQ(testing::RunCli("retarget --quiet --source=" + demo_ + " --target=" + character + " --out=" + full +
                            " --iterations=3", &output), 0) << output;
  Skeleton target;
  Motion retargeted;
  ASSERT_TRUE(ReadBvh(full, &target, &retargeted).ok());
  ASSERT_EQ(retargeted.num_frames(), 121);
  const std::string glb = testing::TempPath("cut.gltf"), bvh = testing::TempPath("cut_out.bvh");
  const std::string report = testing::TempPath("cut.json");
  ASSERT_EQ(testing::RunCli("retarget --quiet --source=" + demo_ + " --target=" + character + " --out=" + glb +
                            " --out_bvh=" + bvh + " --iterations=3 --frames=40: --out_fps=30 --report=" + report,
                            &output), 0) << output;
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"delivered_frames\": 21"));
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadBvh(bvh, &skeleton, &motion).ok());
  EXPECT_EQ(motion.num_frames(), 21);  // Frames 40, 44, ..., 120.
  EXPECT_LT(LargestDistance(target, retargeted, 40, 4, skeleton, motion), 1e-5);  // Metres, 6 digits.
  GltfCharacter written;
  ASSERT_TRUE(ReadGltfCharacter(glb, {}, &written).ok());
  ASSERT_FALSE(written.animation_names.empty());
  EXPECT_EQ(written.animation_names.front(), "retargeted from walk120.bvh");
  Status status = ReadMotionFile(glb, {}, &skeleton, &motion);  // The default clip: the added one.
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(motion.num_frames(), 21);
  EXPECT_LT(LargestDistance(target, retargeted, 40, 4, skeleton, motion), 1e-5);
  EXPECT_EQ(testing::RunCli("retarget --quiet --source=" + demo_ + " --target=" + character + " --out=" +
                            testing::TempPath("none.glb") + " --seconds=2:3", &output), 1);
  EXPECT_THAT(output, HasSubstr("--seconds=2:3: the clip lasts 1 s, 0:1"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  EXPECT_FALSE(testing::FileExists(testing::TempPath("none.glb")));

  // pipeline: markers of the demo walk (1 s at 120 fps), a subject calibrated on it.
  const std::string markers = testing::TempPath("walk120.c3d"), subject = testing::TempPath("S.json");
  ASSERT_EQ(testing::RunCli("markers --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 --noise_mm=0.5 "
                            "--seed=3 --out=" + markers, &output), 0) << output;
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --skeleton_units=cm --markers=" + markers +
                            " --attach=auto --out=" + testing::TempPath("calibrated.json") + " --out_subject=" +
                            subject, &output), 0) << output;
  const std::string whole = testing::TempPath("take_whole"), cut = testing::TempPath("take_cut");
  const std::string pipeline = "pipeline --quiet --view=off --subject=" + subject + " --markers=" + markers +
                               " --character=" + character + " --formats=glb,fbx,bvh --gate_limb_vertices=0 ";  // Figure: 1 vertex a joint.
  ASSERT_EQ(testing::RunCli(pipeline + "--out_dir=" + whole, &output), 0) << output;
  ASSERT_EQ(testing::RunCli(pipeline + "--out_dir=" + cut + " --seconds=0.25:0.75 --out_fps=60", &output), 0)
      << output;
  Skeleton reference_skeleton;
  Motion reference;  // The whole take on the character, as delivered without options.
  ASSERT_TRUE(ReadMotionFile(whole + "/figure.gltf", {}, &reference_skeleton, &reference).ok());
  ASSERT_EQ(reference.num_frames(), 121);
  for (const char* file : {"figure.gltf", "figure.fbx", "figure.bvh"}) {
    status = ReadMotionFile(cut + "/" + file, {}, &skeleton, &motion);
    ASSERT_TRUE(status.ok()) << file << ": " << status.message();
    EXPECT_EQ(motion.num_frames(), 31) << file;  // Frames 30, 32, ..., 90 of the take.
    EXPECT_NEAR(motion.frame_rate, 60.0, 1e-6) << file;
    EXPECT_LT(LargestDistance(reference_skeleton, reference, 30, 2, skeleton, motion), 1e-4) << file;
  }
  // The take's own record keeps its frames.
  Motion solved;
  ASSERT_TRUE(ReadBvh(cut + "/solved.bvh", &skeleton, &solved).ok());
  EXPECT_EQ(solved.num_frames(), 121);
  EXPECT_THAT(testing::ReadTextFile(cut + "/report.json"), HasSubstr("\"delivered_frames\": 31"));
  // Out of the take: an error before any work, nothing written.
  const std::string none = testing::TempPath("take_none");
  EXPECT_EQ(testing::RunCli(pipeline + "--out_dir=" + none + " --frames=100:200", &output), 1);
  EXPECT_THAT(output, HasSubstr("--frames=100:200: the clip has 121 frames, 0:120"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  EXPECT_FALSE(testing::FileExists(none));
}

// A skeleton FBX importers cannot read back (Blender's recurses once per level) is one
// line naming the joint, exit 1, and no file; the same chain one joint shorter is written.
TEST(FbxDelivery, FbxOfASkeletonTooDeepIsAnErrorNamingTheJoint) {
  for (const int joints : {901, 902}) {
    std::string bvh = "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation "
                      "Xrotation Yrotation\n";
    for (int j = 1; j < joints; ++j) bvh += "JOINT j" + std::to_string(j) + "\n{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation "
                                            "Xrotation Yrotation\n";
    for (int j = 0; j < joints; ++j) bvh += "}\n";
    bvh += "MOTION\nFrames: 1\nFrame Time: 0.0333333\n";
    for (int c = 0; c < 3 + 3 * joints; ++c) bvh += c == 0 ? "0" : " 0";
    bvh += "\n";
    const std::string in = testing::TempPath("chain.bvh"), out = testing::TempPath("chain.fbx");
    testing::WriteTextFile(in, bvh);
    std::remove(out.c_str());
    std::string output;
    const int code = testing::RunCli("convert " + in + " " + out, &output);
    if (joints == 901) {
      EXPECT_EQ(code, 0) << output;
      EXPECT_TRUE(testing::FileExists(out));
      continue;
    }
    EXPECT_EQ(code, 1) << output;
    EXPECT_THAT(output, HasSubstr("joint 901 'j901': 901 levels below the root, deeper than the 900"));
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
    EXPECT_FALSE(testing::FileExists(out));
  }
}

}  // namespace
}  // namespace mocapsolve
