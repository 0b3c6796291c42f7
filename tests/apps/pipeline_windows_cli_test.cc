// `mocapsolve pipeline` on a take longer than --window_frames (pipeline/take_windows.h):
// the demo walk (600 frames at 120 Hz, markers synthesized from it, a subject calibrated on
// it) onto a test character, in windows of 200 frames with 50 of context, against the same
// take run whole: every output valid and complete (every frame once, in order) and close
// to the whole run's; with two threads the same bytes as with one; the character's FBX
// beside its GLB; what a windowed take refuses, one line and nothing written.
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <regex>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/bvh_reader.h"
#include "io/fbx_reader.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/json_reader.h"
#include "io/marker_file.h"
#include "kinematics/forward_kinematics.h"
#include "tests/gltf_test_files.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

class PipelineWindowsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk.bvh");
    markers_ = testing::TempPath("walk.c3d");
    subject_ = testing::TempPath("subject.json");
    character_ = testing::TempPath("Dummy.glb");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=600 --fps=120", &output), 0) << output;
    ASSERT_EQ(testing::RunCli("markers --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 --write_markerset=" +
                              testing::TempPath("set.json") + " --noise_mm=0.5 --seed=3 --out=" + markers_, &output),
              0) << output;
    ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                              " --attach=auto --out=" + testing::TempPath("calibrated.json") +
                              " --out_subject=" + subject_, &output), 0) << output;
    const std::string gltf = testing::TempPath("Dummy.gltf");
    testing::WriteTestCharacter(gltf, 45.0);
    GltfDocument document;
    ASSERT_TRUE(GltfDocument::Read(gltf, &document).ok());
    std::string glb;
    ASSERT_TRUE(SerializeGltfAsGlb(document, &glb).ok());
    testing::WriteTextFile(character_, glb);
  }
  int Pipeline(const std::string& dir, const std::string& extra, std::string* output) {
    return testing::RunCli("pipeline --quiet --view=off --subject=" + subject_ + " --markers=" + markers_ +
                           " --character=" + character_ + " --gate_limb_vertices=0 --out_dir=" + dir + " " + extra, output);
  }
  std::string demo_, markers_, subject_, character_;
};

// The largest joint distance between two motions of one skeleton, frame by frame.
double LargestJointDistance(const Skeleton& skeleton, const Motion& a, const Motion& b) {
  FkData fa(skeleton), fb(skeleton);
  double worst = 0.0;
  for (int f = 0; f < std::min(a.num_frames(), b.num_frames()); ++f) {
    ForwardKinematics(skeleton, a.frames[f], &fa);
    ForwardKinematics(skeleton, b.frames[f], &fb);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      worst = std::max(worst, (fa.world_positions[j] - fb.world_positions[j]).norm());
    }
  }
  return worst;
}

Motion CharacterTake(const std::string& path, Skeleton* skeleton = nullptr) {
  GltfDocument document;
  EXPECT_TRUE(GltfDocument::Read(path, &document).ok()) << path;
  GltfCharacter character;
  EXPECT_TRUE(ReadGltfCharacter(document, {}, &character).ok());
  if (skeleton != nullptr) *skeleton = character.skeleton;
  Motion take;
  GltfAnimationOptions options;
  options.animation = "walk";
  EXPECT_TRUE(ReadGltfAnimation(document, character, options, &take).ok());
  return take;
}

TEST_F(PipelineWindowsCli, WindowedTakeIsCompleteAndCloseToTheWholeRun) {
  const std::string whole = testing::TempPath("whole"), windowed = testing::TempPath("windowed");
  std::string output;
  ASSERT_EQ(Pipeline(whole, "", &output), 0) << output;
  ASSERT_EQ(Pipeline(windowed, "--window_frames=200 --window_context_frames=50", &output), 0) << output;
  JsonNode report;
  ASSERT_TRUE(ParseJson(testing::ReadTextFile(windowed + "/report.json"), "report.json", &report).ok());
  const JsonNode* windows = report.Find("windows");
  ASSERT_NE(windows, nullptr);
  EXPECT_EQ(windows->Find("count")->number, 3);
  EXPECT_EQ(windows->Find("frames")->number, 200);
  EXPECT_EQ(windows->Find("seams_mm")->items.size(), 2u);
  EXPECT_EQ(windows->Find("seam_blend_frames")->number, 50);  // The default 60, at most the context.
  EXPECT_EQ(report.Find("frames")->number, 600);
  EXPECT_TRUE(report.Find("quality_gate")->Find("pass")->boolean);
  EXPECT_THAT(testing::ReadTextFile(whole + "/report.json"), ::testing::Not(HasSubstr("\"windows\"")));

  // solved.bvh: every frame, in order, close to the whole run's (the windows' seams).
  Skeleton skeleton, whole_skeleton;
  Motion solved, whole_solved;
  ASSERT_TRUE(ReadBvh(windowed + "/solved.bvh", &skeleton, &solved).ok());
  ASSERT_TRUE(ReadBvh(whole + "/solved.bvh", &whole_skeleton, &whole_solved).ok());
  ASSERT_EQ(solved.num_frames(), 600);
  EXPECT_DOUBLE_EQ(solved.frame_rate, whole_solved.frame_rate);
  const double solve_cm = LargestJointDistance(skeleton, solved, whole_solved);
  EXPECT_LT(solve_cm, 1.0) << "cm";
  RecordProperty("solve_difference_cm", std::to_string(solve_cm));

  // repaired.c3d: the take's frames and labels, each sample close to the whole run's.
  MarkerTrajectories repaired, whole_repaired;
  ASSERT_TRUE(ReadMarkerFile(windowed + "/repaired.c3d", &repaired).ok());
  ASSERT_TRUE(ReadMarkerFile(whole + "/repaired.c3d", &whole_repaired).ok());
  ASSERT_EQ(repaired.num_frames(), 600);
  ASSERT_EQ(repaired.labels(), whole_repaired.labels());
  double marker_difference = 0.0;
  for (int f = 0; f < 600; ++f) {
    for (int m = 0; m < repaired.num_markers(); ++m) {
      ASSERT_EQ(repaired.valid(f, m), whole_repaired.valid(f, m)) << f << " " << m;
      if (repaired.valid(f, m)) {
        marker_difference = std::max(marker_difference, (repaired.position(f, m) - whole_repaired.position(f, m)).norm());
      }
    }
  }
  EXPECT_LT(marker_difference, 1.0);

  // The character's take: every frame, its joints close to the whole run's (metres; the
  // character is 1.75 m tall).
  Skeleton character;
  const Motion take = CharacterTake(windowed + "/Dummy.glb", &character);
  const Motion whole_take = CharacterTake(whole + "/Dummy.glb");
  ASSERT_EQ(take.num_frames(), 600);
  ASSERT_EQ(whole_take.num_frames(), 600);
  const double character_m = LargestJointDistance(character, take, whole_take);
  EXPECT_LT(character_m, 0.05);
  std::printf("windowed against whole: solve %.3f cm, markers %.4f mm, character %.1f mm\n", solve_cm,
              marker_difference, 1000.0 * character_m);
  EXPECT_THAT(output, HasSubstr("quality gate: pass"));
}

// report.json without what may differ between two runs of one take: timings (and the
// repair's stage names, "in parallel" with two threads) and the threads asked for.
std::string WithoutTimings(std::string report) {
  report = std::regex_replace(report, std::regex(R"re("timings": \[[^\]]*\])re"), "");
  return std::regex_replace(report, std::regex(R"re("(\w*seconds|frames_per_second|num_threads|threads)": [^,}\n]*)re"),
                            "");
}

// With --num_threads=2 the windows' character stages run on a second thread beside the
// next windows' repairs: every file is the bytes of the one-thread run (the characters'
// frames appended in window order, the figures summed in window order).
TEST_F(PipelineWindowsCli, TwoThreadsWriteTheBytesOfOne) {
  const std::string one = testing::TempPath("one_thread"), two = testing::TempPath("two_threads");
  std::string output;
  const std::string windows = "--window_frames=150 --window_context_frames=50 --formats=glb,fbx,bvh ";
  ASSERT_EQ(Pipeline(one, windows + "--num_threads=1", &output), 0) << output;
  ASSERT_EQ(Pipeline(two, windows + "--num_threads=2", &output), 0) << output;
  for (const std::string file : {"repaired.c3d", "solved.bvh", "Dummy.glb", "Dummy.fbx", "Dummy.bvh"}) {
    const std::string bytes = testing::ReadTextFile(one + "/" + file);
    EXPECT_FALSE(bytes.empty()) << file;
    EXPECT_TRUE(bytes == testing::ReadTextFile(two + "/" + file)) << file << " differs";
  }
  const std::string report_one = testing::ReadTextFile(one + "/report.json");
  const std::string report_two = testing::ReadTextFile(two + "/report.json");
  EXPECT_EQ(WithoutTimings(report_one), WithoutTimings(report_two));
  JsonNode report;
  ASSERT_TRUE(ParseJson(report_two, "report.json", &report).ok());
  ASSERT_NE(report.Find("windows"), nullptr);
  ASSERT_NE(report.Find("windows")->Find("threads"), nullptr);
  EXPECT_EQ(report.Find("windows")->Find("count")->number, 4);
  EXPECT_EQ(report.Find("windows")->Find("threads")->number, 2);
  ASSERT_TRUE(ParseJson(report_one, "report.json", &report).ok());
  EXPECT_EQ(report.Find("windows")->Find("threads")->number, 1);
}

// The character's FBX and BVH of a windowed take are written from its compact take, as its
// GLB: the same frames (every frame once, in order), the same joints' motion (FBX keys are
// floats, BVH numbers 6 digits).
TEST_F(PipelineWindowsCli, WindowedTakeWritesTheCharactersFbxAndBvhAsItsGlb) {
  const std::string dir = testing::TempPath("windowed_fbx");
  std::string output;
  ASSERT_EQ(Pipeline(dir, "--window_frames=200 --window_context_frames=50 --formats=fbx,glb,bvh", &output), 0)
      << output;
  Skeleton skeleton;
  const Motion glb = CharacterTake(dir + "/Dummy.glb", &skeleton);
  Skeleton fbx_skeleton;
  Motion fbx;
  ASSERT_TRUE(ReadFbx(dir + "/Dummy.fbx", FbxReadOptions(), &fbx_skeleton, &fbx).ok());
  ASSERT_EQ(fbx.num_frames(), 600);
  ASSERT_EQ(glb.num_frames(), 600);
  EXPECT_DOUBLE_EQ(fbx.frame_rate, glb.frame_rate);
  ASSERT_EQ(fbx_skeleton.name(0), skeleton.name(0));
  // The root's path, frame by frame (the reader gives the file's centimetres back in the
  // character's metres).
  double worst_m = 0.0;
  for (int f = 0; f < 600; ++f) {
    worst_m = std::max(worst_m, (fbx.frames[f].translations[0] - glb.frames[f].translations[0]).norm());
  }
  EXPECT_LT(worst_m, 1e-5);
  Skeleton bvh_skeleton;
  Motion bvh;
  ASSERT_TRUE(ReadBvh(dir + "/Dummy.bvh", &bvh_skeleton, &bvh).ok());
  ASSERT_EQ(bvh.num_frames(), 600);
  EXPECT_NEAR(LargestJointDistance(skeleton, glb, bvh), 0.0, 1e-4);  // Metres.
}

// A window whose context reaches back to frame 0 has no frame before it: it starts as the
// first window does (it read a pose before the previous window's first frame, out of
// bounds, and its results changed from run to run). With a context as long as the take
// every window solves the whole take, so every window's core is the whole run's.
TEST_F(PipelineWindowsCli, AWindowWhoseContextReachesFrameZeroStartsAsTheFirst) {
  const std::string whole = testing::TempPath("whole_for_context"), windowed = testing::TempPath("wide_context");
  std::string output;
  ASSERT_EQ(Pipeline(whole, "--num_threads=1", &output), 0) << output;
  ASSERT_EQ(Pipeline(windowed, "--num_threads=1 --window_frames=150 --window_context_frames=600", &output), 0)
      << output;
  EXPECT_TRUE(testing::ReadTextFile(whole + "/solved.bvh") == testing::ReadTextFile(windowed + "/solved.bvh"));
}

TEST_F(PipelineWindowsCli, RefusesWhatAWindowedTakeCannotWrite) {
  const std::string dir = testing::TempPath("refused");
  std::string output;
  EXPECT_EQ(Pipeline(dir, "--window_frames=200 --out_fps=30", &output), 1);
  EXPECT_THAT(output, HasSubstr("delivered whole"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  struct stat st;
  EXPECT_NE(::stat(dir.c_str(), &st), 0) << "nothing written";
  // The same take within its window runs whole, as before.
  ASSERT_EQ(Pipeline(dir, "--window_frames=600", &output), 0) << output;
  EXPECT_THAT(testing::ReadTextFile(dir + "/report.json"), ::testing::Not(HasSubstr("\"windows\"")));
}

}  // namespace
}  // namespace mocapsolve
