// `mocapsolve pipeline` end to end on a take the project makes (the demo walk, markers
// synthesized from it, a subject calibrated on it), and its bad inputs: one line naming
// the file, exit 1, nothing written to the output folder.
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "io/bvh_reader.h"
#include "io/gltf_reader.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

bool FolderExists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

class PipelineCli : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk.bvh");
    markers_ = testing::TempPath("walk.c3d");
    set_ = testing::TempPath("set.json");
    subject_ = testing::TempPath("subject.json");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=60 --fps=30", &output), 0) << output;
    ASSERT_EQ(testing::RunCli("markers --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 "
                              "--write_markerset=" + set_ + " --noise_mm=0.5 --seed=3 --out=" + markers_, &output),
              0) << output;
    ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                              " --attach=auto --out=" + testing::TempPath("calibrated.json") +
                              " --out_subject=" + subject_, &output), 0) << output;
  }
  int Pipeline(const std::string& extra, std::string* output) {
    return testing::RunCli("pipeline --quiet --subject=" + subject_ + " " + extra, output);
  }
  std::string demo_, markers_, set_, subject_;
};

TEST_F(PipelineCli, SolvesTheTakeAndWritesTheOutputs) {
  const std::string dir = testing::TempPath("out");
  std::string output;
  ASSERT_EQ(Pipeline("--markers=" + markers_ + " --out_dir=" + dir + " --filter_levels=1", &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("quality gate: pass"));
  EXPECT_TRUE(testing::FileExists(dir + "/repaired.c3d"));
  const std::string report = testing::ReadTextFile(dir + "/report.json");
  EXPECT_THAT(report, HasSubstr("\"pass\": true"));
  EXPECT_THAT(report, HasSubstr("\"version\""));
  Skeleton skeleton;
  Motion solved;
  ASSERT_TRUE(ReadBvh(dir + "/solved.bvh", &skeleton, &solved).ok());
  EXPECT_EQ(solved.num_frames(), 60);
}

// --animation_only: DIR/Xbot.glb holds Xbot's skeleton, skin and the take, no meshes.
TEST_F(PipelineCli, AnimationOnlyCharacterFiles) {
  MOCAPSOLVE_DATA_FILE(xbot, "gltf/Xbot.glb");
  const std::string dir = testing::TempPath("slim");
  const std::string report = testing::TempPath("slim.json");
  std::string output;
  ASSERT_EQ(Pipeline("--markers=" + markers_ + " --out_dir=" + dir + " --character=" + xbot +
                     " --animation_only --report=" + report, &output), 0) << output;
  GltfDocument document;
  ASSERT_TRUE(GltfDocument::Read(dir + "/Xbot.glb", &document).ok());
  const tinygltf::Model& model = document.model();
  EXPECT_TRUE(model.meshes.empty());
  EXPECT_TRUE(model.materials.empty());
  ASSERT_EQ(model.animations.size(), 1u);
  EXPECT_EQ(model.animations[0].name, "walk");
  ASSERT_EQ(model.skins.size(), 1u);
  EXPECT_EQ(model.skins[0].joints.size(), 65u);
  struct stat written, character;
  ASSERT_EQ(::stat((dir + "/Xbot.glb").c_str(), &written), 0);
  ASSERT_EQ(::stat(xbot.c_str(), &character), 0);
  EXPECT_LT(written.st_size, character.st_size / 10);  // 1.84 MB; 60 frames: 99 kB.
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"animation_only\": true"));
  EXPECT_THAT(testing::ReadTextFile(dir + "/report.json"), HasSubstr("\"animation_only\": true"));
}

TEST_F(PipelineCli, ConfigFileAndFlagsAndPrintConfig) {
  std::string output;
  ASSERT_EQ(testing::RunCli("pipeline --print_config", &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("\"dp_max_cm\": 10"));
  EXPECT_THAT(output, HasSubstr("\"animation_only\": false"));
  EXPECT_THAT(output, HasSubstr("\"gate_repaired_rms_mm\": 20"));
  const std::string config = testing::TempPath("config.json");
  ASSERT_EQ(testing::RunCli("pipeline --print_config --gate_repaired_rms_mm=5", &output), 0);
  EXPECT_THAT(output, HasSubstr("\"gate_repaired_rms_mm\": 5"));
  // A config file sets what the command line does not.
  {
    std::FILE* file = std::fopen(config.c_str(), "w");
    std::fputs("{\"gate_naive_rms_mm\": 0.001, \"filter_levels\": 1}\n", file);
    std::fclose(file);
  }
  ASSERT_EQ(testing::RunCli("pipeline --print_config --config=" + config + " --filter_levels=2", &output), 0);
  EXPECT_THAT(output, HasSubstr("\"gate_naive_rms_mm\": 0.001"));
  EXPECT_THAT(output, HasSubstr("\"filter_levels\": 2"));
  // A gate the take cannot pass: exit 3, outputs written, the report says why.
  const std::string dir = testing::TempPath("gated");
  EXPECT_EQ(Pipeline("--markers=" + markers_ + " --out_dir=" + dir + " --config=" + config, &output), 3) << output;
  EXPECT_THAT(output, HasSubstr("quality gate failed: naive marker RMS"));
  EXPECT_THAT(testing::ReadTextFile(dir + "/report.json"), HasSubstr("\"pass\": false"));
  // A printed config read back changes nothing (the solver included: dls by default).
  ASSERT_EQ(testing::RunCli("pipeline --print_config", &output), 0);
  EXPECT_THAT(output, HasSubstr("\"solver\": \"dls\""));
  const std::string printed = testing::TempPath("printed.json");
  {
    std::FILE* file = std::fopen(printed.c_str(), "w");
    std::fputs(output.c_str(), file);
    std::fclose(file);
  }
  std::string again;
  ASSERT_EQ(testing::RunCli("pipeline --print_config --config=" + printed, &again), 0) << again;
  EXPECT_EQ(again, output);
  // Unknown keys are errors naming the file and key.
  {
    std::FILE* file = std::fopen(config.c_str(), "w");
    std::fputs("{\"dp_max_cn\": 3}\n", file);
    std::fclose(file);
  }
  EXPECT_EQ(testing::RunCli("pipeline --print_config --config=" + config, &output), 1);
  EXPECT_THAT(output, HasSubstr("unknown option 'dp_max_cn'"));
}

TEST_F(PipelineCli, BadInputsWriteNothing) {
  const std::string dir = testing::TempPath("bad");
  std::string output;
  // A character without a skin (a plain text file named .glb).
  const std::string not_a_character = testing::TempPath("flat.glb");
  {
    std::FILE* file = std::fopen(not_a_character.c_str(), "w");
    std::fputs("not a glb", file);
    std::fclose(file);
  }
  EXPECT_EQ(Pipeline("--markers=" + markers_ + " --out_dir=" + dir + " --character=" + not_a_character, &output), 1);
  EXPECT_THAT(output, HasSubstr("flat.glb"));
  // A take of 0 frames, and a subject pointing at a missing skeleton.
  EXPECT_EQ(Pipeline("--markers=" + testing::TempPath("none.c3d") + " --out_dir=" + dir, &output), 1);
  EXPECT_THAT(output, HasSubstr("none.c3d"));
  // A marker file whose labels match none of the subject's markers.
  const std::string other = testing::TempPath("other.trc");
  {
    std::FILE* file = std::fopen(other.c_str(), "w");
    std::fputs("PathFileType\t4\t(X/Y/Z)\tother.trc\n"
               "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames\n"
               "30\t30\t2\t1\tmm\t30\t1\t2\n"
               "Frame#\tTime\tNOPE\t\t\n"
               "\t\tX1\tY1\tZ1\n"
               "1\t0\t1\t2\t3\n"
               "2\t0.0333\t1\t2\t3\n", file);
    std::fclose(file);
  }
  EXPECT_EQ(Pipeline("--markers=" + other + " --out_dir=" + dir, &output), 1);
  EXPECT_THAT(output, HasSubstr("other.trc"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  // A subject (written as older files are, the skeleton by path) whose skeleton file is missing.
  const std::string broken = testing::TempPath("broken_subject.json");
  {
    std::string text = testing::ReadTextFile(subject_);
    const size_t key = text.find("  \"skeleton\": {"), end = text.find("  \"marker_files\"");
    ASSERT_NE(key, std::string::npos) << text.substr(0, 300);
    ASSERT_NE(end, std::string::npos) << text.substr(0, 300);
    text.replace(key, end - key, "  \"skeleton\": \"no_such_skeleton.bvh\",\n  \"skeleton_units\": \"cm\",\n");
    std::FILE* file = std::fopen(broken.c_str(), "w");
    std::fputs(text.c_str(), file);
    std::fclose(file);
  }
  EXPECT_EQ(testing::RunCli("pipeline --quiet --subject=" + broken + " --markers=" + markers_ + " --out_dir=" + dir,
                            &output), 1);
  EXPECT_THAT(output, HasSubstr("broken_subject.json"));
  EXPECT_FALSE(FolderExists(dir));
}

// The take's page: by default (--view=auto) written when the viewer's runtime is installed
// and skipped with a warning when it is not; asked for (--view=PAGE.html) without the
// runtime, an error before any work and nothing written; --view=off, none.
TEST_F(PipelineCli, ViewPageDefaultAndRequired) {
  setenv("MOCAPSOLVE_VIEWER_TOOLS", testing::TempPath("no_viewer_tools").c_str(), 1);
  std::string output;
  const std::string auto_dir = testing::TempPath("view_auto");
  EXPECT_EQ(Pipeline("--markers=" + markers_ + " --out_dir=" + auto_dir, &output), 0) << output;  // --quiet too.
  EXPECT_THAT(output, HasSubstr("warning: pipeline: no view.html (--view=auto)"));
  EXPECT_THAT(output, HasSubstr("scripts/viewer_tools.sh"));
  EXPECT_TRUE(testing::FileExists(auto_dir + "/solved.bvh"));
  EXPECT_FALSE(testing::FileExists(auto_dir + "/view.html"));
  EXPECT_THAT(testing::ReadTextFile(auto_dir + "/report.json"), HasSubstr("\"view\": null"));

  const std::string asked_dir = testing::TempPath("view_asked");
  EXPECT_EQ(Pipeline("--markers=" + markers_ + " --out_dir=" + asked_dir + " --view=" + asked_dir + "/view.html",
                     &output), 1);
  EXPECT_THAT(output, HasSubstr("--view=" + asked_dir + "/view.html: the viewer's three.js runtime is not installed"));
  EXPECT_THAT(output, HasSubstr("scripts/viewer_tools.sh"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  EXPECT_FALSE(FolderExists(asked_dir));
  // The same for the commands whose --view asks for a page.
  const std::string solved = testing::TempPath("view_asked.bvh");
  EXPECT_EQ(testing::RunCli("solve --quiet --subject=" + subject_ + " --markers=" + markers_ + " --out=" + solved +
                            " --view=" + testing::TempPath("solve.html"), &output), 1);
  EXPECT_THAT(output, HasSubstr("scripts/viewer_tools.sh"));
  EXPECT_FALSE(testing::FileExists(solved));

  const std::string off_dir = testing::TempPath("view_off");
  EXPECT_EQ(testing::RunCli("pipeline --subject=" + subject_ + " --markers=" + markers_ + " --out_dir=" + off_dir +
                            " --view=off", &output), 0) << output;
  EXPECT_THAT(output, ::testing::Not(HasSubstr("warning")));
  EXPECT_FALSE(testing::FileExists(off_dir + "/view.html"));
  unsetenv("MOCAPSOLVE_VIEWER_TOOLS");
}

// Real data: CMU subject 2 calibrated once on 02_01, then 02_05 (1854 frames) onto Xbot
// end to end; and the same subject on another actor's take, which the gate must stop.
class PipelineRealData : public ::testing::Test {
 protected:
  void SetUp() override {
    MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
    MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
    MOCAPSOLVE_DATA_FILE(c3d, "c3d/02_01.c3d");
    subject_ = testing::TempPath("S02.json");
    std::string output;
    ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + amc + " --skeleton=" + asf + " --markers=" + c3d +
                              " --axes=y,z,x --out=" + testing::TempPath("02.json") + " --out_subject=" + subject_,
                              &output), 0) << output;
  }
  std::string subject_;
};

TEST_F(PipelineRealData, Cmu0205OntoXbot) {
  MOCAPSOLVE_DATA_FILE(take, "c3d/cmu_02_05.c3d");
  MOCAPSOLVE_DATA_FILE(xbot, "gltf/Xbot.glb");
  const std::string dir = testing::TempPath("02_05");
  std::string output;
  ASSERT_EQ(testing::RunCli("pipeline --quiet --subject=" + subject_ + " --markers=" + take + " --character=" + xbot +
                            " --out_dir=" + dir, &output), 0) << output;
  GltfCharacter character;
  ASSERT_TRUE(ReadGltfCharacter(dir + "/Xbot.glb", GltfReadOptions(), &character).ok());
  EXPECT_EQ(character.animation_names.back(), "cmu_02_05");
  GltfDocument document;
  ASSERT_TRUE(GltfDocument::Read(dir + "/Xbot.glb", &document).ok());
  GltfAnimationOptions animation;
  animation.animation = "cmu_02_05";
  Motion motion;
  ASSERT_TRUE(ReadGltfAnimation(document, character, animation, &motion).ok());
  EXPECT_NEAR(motion.num_frames(), 1854, 1);
  const std::string report = testing::ReadTextFile(dir + "/report.json");
  EXPECT_THAT(report, HasSubstr("\"pass\": true"));
  EXPECT_THAT(report, HasSubstr("\"stage\": \"retarget onto Xbot\""));
  EXPECT_TRUE(testing::FileExists(dir + "/repaired.c3d"));
}

// Another actor's take through subject 2's marker set: the solve "succeeds" with a
// plausible repaired residual, and only the gate says it is wrong (exit 3).
TEST_F(PipelineRealData, WrongSubjectFailsTheGate) {
  MOCAPSOLVE_DATA_FILE(take, "c3d/cmu_dribble_shoot_basketball.c3d");
  const std::string dir = testing::TempPath("dribble");
  std::string output;
  EXPECT_EQ(testing::RunCli("pipeline --quiet --subject=" + subject_ + " --markers=" + take + " --out_dir=" + dir,
                            &output), 3) << output;
  EXPECT_THAT(output, HasSubstr("quality gate failed: naive marker RMS"));
  EXPECT_THAT(testing::ReadTextFile(dir + "/report.json"), HasSubstr("\"pass\": false"));
}

}  // namespace
}  // namespace mocapsolve
