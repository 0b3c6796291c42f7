// The CLI on glTF and FBX input: info (also of characters without animation), convert to
// BVH (FK of the BVH equals FK of the source), fk, and --animation selection.
#include <string>
#include <utility>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/bvh_reader.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
#include "tests/gltf_test_files.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// Converts `source` to BVH with the CLI and compares FK of every frame.
void ExpectConvertKeepsFk(const std::string& source, const std::string& animation, double size) {
  const std::string bvh = testing::TempPath("converted.bvh");
  std::string output;
  const std::string flag = animation.empty() ? "" : " --animation=" + animation;
  ASSERT_EQ(testing::RunCli("convert " + source + " " + bvh + flag + " --precision=12", &output), 0) << output;
  Skeleton a, b;
  Motion ma, mb;
  MotionFileOptions options;
  options.animation = animation;
  ASSERT_TRUE(ReadMotionFile(source, options, &a, &ma).ok());
  const Status status = ReadBvh(bvh, &b, &mb);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(a.num_joints(), b.num_joints());
  ASSERT_EQ(ma.num_frames(), mb.num_frames());
  EXPECT_NEAR(ma.frame_rate, mb.frame_rate, 1e-9 * ma.frame_rate);
  FkData fa(a), fb(b);
  for (int f = 0; f < ma.num_frames(); ++f) {
    ForwardKinematics(a, ma.frames[f], &fa);
    ForwardKinematics(b, mb.frames[f], &fb);
    for (int j = 0; j < a.num_joints(); ++j) {
      // 1e-9 of the size: 12 significant digits in the BVH.
      ASSERT_LT((fa.world_positions[j] - fb.world_positions[j]).norm(), 1e-9 * size)
          << source << " frame " << f << " joint " << a.name(j);
    }
  }
}

TEST(GltfFbxCli, ConvertGlbToBvhKeepsFk) {
  MOCAPSOLVE_DATA_FILE(path, "gltf/Soldier.glb");
  ExpectConvertKeepsFk(path, "Run", 1.0);
  MOCAPSOLVE_DATA_FILE(cesium, "gltf/CesiumMan.glb");
  ExpectConvertKeepsFk(cesium, "", 2.0);
}

TEST(GltfFbxCli, ConvertFbxToBvhKeepsFk) {
  MOCAPSOLVE_DATA_FILE(path, "fbx/09_11_cmu.fbx");
  ExpectConvertKeepsFk(path, "", 5000.0);
}

TEST(GltfFbxCli, InfoAndFk) {
  MOCAPSOLVE_DATA_FILE(path, "gltf/RobotExpressive.glb");
  std::string output;
  ASSERT_EQ(testing::RunCli("info " + path + " --animation=Running", &output), 0) << output;
  EXPECT_NE(output.find("joints:    43"), std::string::npos) << output;
  EXPECT_NE(output.find("units:     m"), std::string::npos) << output;
  EXPECT_EQ(testing::RunCli("info " + path + " --animation=Flying", &output), 1) << output;
  EXPECT_NE(output.find("no animation 'Flying' (animations: 0 'Dance'"), std::string::npos) << output;
  const std::string csv = testing::TempPath("fk.csv");
  ASSERT_EQ(testing::RunCli("fk --motion=" + path + " --animation=5 --out=" + csv + " --quiet", &output), 0)
      << output;
  EXPECT_NE(testing::ReadTextFile(csv).find("Hips"), std::string::npos);
  // --animation only applies to formats that hold several clips.
  MOCAPSOLVE_DATA_FILE(bvh, "bvh/16_15.bvh");
  EXPECT_EQ(testing::RunCli("info " + bvh + " --animation=1", &output), 1) << output;
  EXPECT_NE(output.find("applies to .glb/.gltf/.fbx only"), std::string::npos) << output;
}

using ::testing::HasSubstr;

// A rigged character without animation (the most common asset): info describes it and
// tells its bind pose from the upper arms.
TEST(GltfFbxCli, InfoOnACharacterWithoutAnimation) {
  const struct {
    double arm_degrees;
    const char* kind;
  } cases[] = {{0.0, "T-pose"}, {40.0, "A-pose"}, {85.0, "other"}, {-20.0, "other"}};
  for (const auto& c : cases) {
    const std::string path = testing::TempPath("character.gltf"), report = testing::TempPath("character.json");
    testing::WriteTestCharacter(path, c.arm_degrees);
    std::string output;
    ASSERT_EQ(testing::RunCli("info " + path + " --report=" + report, &output), 0) << output;
    EXPECT_THAT(output, HasSubstr("joints:    19 (+0 end sites), root 'Hips'")) << output;
    EXPECT_THAT(output, HasSubstr("level 1: 3 joints: Spine, LeftUpLeg, RightUpLeg")) << output;
    EXPECT_THAT(output, HasSubstr("level 2: 3 joints: Spine1, LeftLeg, RightLeg")) << output;
    EXPECT_THAT(output, HasSubstr("meshes:    1 (1 skinned), 1 primitives, 21 vertices")) << output;
    EXPECT_THAT(output, HasSubstr("skins:     1; skin 0 'body': 21 vertices skinned")) << output;
    EXPECT_THAT(output, HasSubstr("height:    1.750 m (bind-pose mesh, along +Y)")) << output;
    EXPECT_THAT(output, HasSubstr(std::string("bind pose: ") + c.kind)) << output;
    EXPECT_THAT(output, HasSubstr("animations: none")) << output;
    if (std::string(c.kind) != "other") {
      EXPECT_THAT(output, HasSubstr("LeftArm -> LeftForeArm")) << output;
      char angles[64];
      std::snprintf(angles, sizeof(angles), "upper arms %.1f and %.1f deg below horizontal", c.arm_degrees,
                    c.arm_degrees);
      EXPECT_THAT(output, HasSubstr(angles)) << output;
    }
    const std::string json = testing::ReadTextFile(report);
    EXPECT_THAT(json, HasSubstr(std::string("\"bind_pose\": \"") + c.kind + "\""));
    EXPECT_THAT(json, HasSubstr("\"animations\": []"));
    EXPECT_THAT(json, HasSubstr("\"root\": \"Hips\""));
  }
  // --animation on a file without one: one line, exit 1.
  const std::string path = testing::TempPath("character.gltf");
  std::string output;
  EXPECT_EQ(testing::RunCli("info " + path + " --animation=Walk", &output), 1);
  EXPECT_EQ(output, "mocapsolve info: " + path + ": --animation=Walk: the file has no animation\n");
}

// The same character as an FBX without animation: the skeleton from its skin's bones.
TEST(GltfFbxCli, InfoOnAnFbxCharacterWithoutAnimation) {
  for (const auto& [degrees, kind] : {std::pair<double, std::string>{0.0, "T-pose"}, {40.0, "A-pose"}}) {
    const std::string path = testing::TempPath("character.fbx"), report = testing::TempPath("fbx_character.json");
    testing::WriteTestCharacterFbx(path, degrees);
    std::string output;
    ASSERT_EQ(testing::RunCli("info " + path + " --report=" + report, &output), 0) << output;
    EXPECT_THAT(output, HasSubstr("meshes:    1 (1 skinned), 21 vertices; 19 bones")) << output;
    EXPECT_THAT(output, HasSubstr("joints:    19 (+0 end sites), root 'Hips'")) << output;
    EXPECT_THAT(output, HasSubstr("height:    1.750 m (175 cm) (bind-pose mesh, along +Y)")) << output;
    EXPECT_THAT(output, HasSubstr("bind pose: " + kind)) << output;
    EXPECT_THAT(output, HasSubstr("animations: none")) << output;
    EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"bind_pose\": \"" + kind + "\""));
  }
  // Motion commands still need an animation.
  std::string output;
  EXPECT_EQ(testing::RunCli("convert " + testing::TempPath("character.fbx") + " " + testing::TempPath("c.bvh"), &output),
            1);
  EXPECT_THAT(output, HasSubstr("has no animation"));
}

// The shared characters (and two skeleton files): each described, the bind poses as their
// files have them (CesiumMan and RiggedFigure: Z up, arms 27 deg down).
TEST(GltfFbxCli, InfoOnTheSharedCharacters) {
  const struct {
    const char* file;
    const char* kind;
  } cases[] = {{"gltf/Xbot.glb", "T-pose"},          {"gltf/CesiumMan.glb", "A-pose (upper arms 26.9"},
               {"gltf/RiggedFigure.glb", "A-pose"},  {"gltf/RobotExpressive.glb", "T-pose"},
               {"gltf/Fox.glb", "other"},            {"amc/02.asf", "T-pose"},
               {"bvh/16_15.bvh", "other (upper arms 90.0 and 90.0"}};  // Its zero pose: arms down.
  for (const auto& c : cases) {
    MOCAPSOLVE_DATA_FILE(path, c.file);
    std::string output;
    ASSERT_EQ(testing::RunCli("info " + path, &output), 0) << output;
    EXPECT_THAT(output, HasSubstr("height:")) << output;
    EXPECT_THAT(output, HasSubstr(std::string("bind pose: ") + c.kind)) << output;
  }
}

TEST(GltfFbxCli, SkeletonFilesAndWarnings) {
  MOCAPSOLVE_DATA_FILE(glb, "gltf/Xbot.glb");
  MOCAPSOLVE_DATA_FILE(fbx, "fbx/08_02_cmu.fbx");
  Skeleton skeleton;
  ASSERT_TRUE(ReadSkeletonFile(glb, &skeleton).ok());
  EXPECT_EQ(skeleton.num_joints(), 65);
  EXPECT_EQ(skeleton.unit().name, "m");
  ASSERT_TRUE(ReadSkeletonFile(fbx, &skeleton).ok());
  EXPECT_EQ(skeleton.num_joints(), 31);
  std::vector<std::string> clips;
  ASSERT_TRUE(ReadAnimationNames(glb, &clips).ok());
  EXPECT_EQ(clips, std::vector<std::string>{"Armature|mixamo.com|Layer0"});
  // RobotExpressive's legs have a slightly non-uniform scale: a warning, on stderr in the CLI.
  MOCAPSOLVE_DATA_FILE(robot, "gltf/RobotExpressive.glb");
  std::vector<std::string> warnings;
  MotionFileOptions options;
  options.warnings = &warnings;
  Motion motion;
  ASSERT_TRUE(ReadMotionFile(robot, options, &skeleton, &motion).ok());
  // Its left hand is bound to a second skin over the same joints, read with the character (the
  // third), and its body is rigid meshes under its bones (io/gltf_rigid_parts.h): the fourth.
  ASSERT_EQ(warnings.size(), 4u);
  EXPECT_NE(warnings[0].find("'Leg.R': non-uniform or negative scale"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[2].find("skin 1's meshes (554 vertices) are bound to skin 0's joints"), std::string::npos)
      << warnings[2];
  EXPECT_NE(warnings[3].find("12 mesh nodes parented to its bones are rigid parts"), std::string::npos) << warnings[3];
  std::string output;
  ASSERT_EQ(testing::RunCli("info " + robot, &output), 0);
  EXPECT_NE(output.find("warning: " + warnings[0]), std::string::npos) << output;
}

// glTF -> BVH -> back into the character as a new clip: FK equals the original clip's.
TEST(GltfFbxCli, BvhBackIntoTheCharacter) {
  MOCAPSOLVE_DATA_FILE(soldier, "gltf/Soldier.glb");
  const std::string bvh = testing::TempPath("run.bvh");
  const std::string glb = testing::TempPath("soldier_run.glb");
  std::string output;
  ASSERT_EQ(testing::RunCli("convert " + soldier + " " + bvh + " --animation=Run --precision=12", &output), 0)
      << output;
  ASSERT_EQ(testing::RunCli("convert " + bvh + " " + glb + " --target=" + soldier + " --clip_name=RunAgain", &output),
            0)
      << output;
  Skeleton a, b;
  Motion ma, mb;
  MotionFileOptions options;
  options.animation = "Run";
  ASSERT_TRUE(ReadMotionFile(soldier, options, &a, &ma).ok());
  options.animation = "RunAgain";
  const Status status = ReadMotionFile(glb, options, &b, &mb);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(ma.num_frames(), mb.num_frames());
  FkData fa(a), fb(b);
  for (int f = 0; f < ma.num_frames(); ++f) {
    ForwardKinematics(a, ma.frames[f], &fa);
    ForwardKinematics(b, mb.frames[f], &fb);
    for (int j = 0; j < a.num_joints(); ++j) {
      // 1e-6 m on a 0.2 m figure: float keys in the glTF, 12 digits in the BVH.
      ASSERT_LT((fa.world_positions[j] - fb.world_positions[j]).norm(), 1e-6) << "frame " << f << " joint " << j;
    }
  }
  // Another character's skeleton does not fit: one line, exit 1.
  MOCAPSOLVE_DATA_FILE(xbot, "gltf/Xbot.glb");
  EXPECT_EQ(testing::RunCli("convert " + bvh + " " + testing::TempPath("x.glb") + " --target=" + xbot, &output), 1);
  EXPECT_NE(output.find("offset differs"), std::string::npos) << output;
  EXPECT_EQ(testing::RunCli("convert " + bvh + " " + testing::TempPath("y.glb"), &output), 1);
  EXPECT_NE(output.find("needs --target"), std::string::npos) << output;
}

}  // namespace
}  // namespace mocapsolve
