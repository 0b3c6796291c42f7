// `mocapsolve retarget` end to end on the shared glTF characters (skipped without the
// data): CesiumMan's walk onto RiggedFigure (different names and proportions) by both
// solvers, the report's figures, and the bad inputs (missing file, unknown solver and
// animation, bad blend-mask file, output over an input) as one-line errors with exit 1.
// Skeleton-only sources: a CMU BVH walk onto Xbot, and their bad inputs (a target without
// a skin, a joint map naming an unknown joint, a source that cannot be aligned).
// --root_motion: RobotExpressive's run onto itself with its root bone carrying the track;
// on Xbot (the hips are the root) an error; an unknown mode an error; --stride=legs noted.
#include <algorithm>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "io/bvh_reader.h"
#include "io/gltf_reader.h"
#include "io/json_reader.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

TEST(RetargetCli, CesiumManOntoRiggedFigureByBothSolvers) {
  MOCAPSOLVE_DATA_FILE(source, "gltf/CesiumMan.glb");
  MOCAPSOLVE_DATA_FILE(target, "gltf/RiggedFigure.glb");
  for (const char* solver : {"dls", "ceres"}) {
    const std::string out = testing::TempPath(std::string(solver) + ".bvh");
    const std::string report = testing::TempPath(std::string(solver) + ".json");
    std::string output;
    ASSERT_EQ(testing::RunCli("retarget --quiet --source=" + source + " --target=" + target + " --out=" + out +
                                  " --solver=" + solver + " --iterations=5 --max_frames=12 --report=" + report,
                              &output),
              0)
        << output;
    Skeleton skeleton;
    Motion motion;
    ASSERT_TRUE(ReadBvh(out, &skeleton, &motion).ok());
    EXPECT_EQ(motion.num_frames(), 12);
    EXPECT_EQ(skeleton.num_joints(), 19);
    JsonNode root;
    ASSERT_TRUE(ReadJsonFile(report, &root).ok());
    const JsonNode* error = root.Find("mean_position_error_fraction_of_height");
    const JsonNode* normal = root.Find("mean_normal_error_deg");
    const JsonNode* frames = root.Find("per_frame_position_error");
    ASSERT_TRUE(error != nullptr && normal != nullptr && frames != nullptr);
    EXPECT_EQ(frames->items.size(), 12u);
    // Different proportions: the tracked vertices cannot all be matched; measured ~0.045 of
    // the height and ~4-5 degrees for both solvers. Bounds with headroom, but tight enough
    // to catch a broken mapping or facing (0.2 and 60+ degrees).
    EXPECT_LT(error->number, 0.08) << solver;
    EXPECT_LT(normal->number, 10.0) << solver;
  }
}

// A .glb output is the target file plus the result as a new animation that reads back.
TEST(RetargetCli, WritesTheResultIntoTheTargetGlb) {
  MOCAPSOLVE_DATA_FILE(source, "gltf/CesiumMan.glb");
  MOCAPSOLVE_DATA_FILE(target, "gltf/RiggedFigure.glb");
  const std::string out = testing::TempPath("out.glb");
  const std::string bvh = testing::TempPath("out.bvh");
  std::string output;
  ASSERT_EQ(testing::RunCli("retarget --quiet --source=" + source + " --target=" + target + " --out=" + out +
                                " --out_bvh=" + bvh + " --iterations=3 --max_frames=6 --animation_name=walk",
                            &output),
            0)
      << output;
  GltfDocument document;
  ASSERT_TRUE(GltfDocument::Read(out, &document).ok());
  GltfCharacter character;
  ASSERT_TRUE(ReadGltfCharacter(document, GltfReadOptions(), &character).ok());
  EXPECT_EQ(character.animation_names.size(), 2u);
  GltfAnimationOptions options;
  options.animation = "walk";
  Motion from_glb;
  ASSERT_TRUE(ReadGltfAnimation(document, character, options, &from_glb).ok());
  Skeleton skeleton;
  Motion from_bvh;
  ASSERT_TRUE(ReadBvh(bvh, &skeleton, &from_bvh).ok());
  EXPECT_EQ(from_glb.num_frames(), 6);
  EXPECT_EQ(from_bvh.num_frames(), 6);
}

// --animation_only: the target's skeleton, skin and the new animation, no meshes; the
// report records the option; a .bvh --out with it is an error.
TEST(RetargetCli, AnimationOnlyGlb) {
  MOCAPSOLVE_DATA_FILE(source, "gltf/CesiumMan.glb");
  MOCAPSOLVE_DATA_FILE(target, "gltf/RiggedFigure.glb");
  const std::string out = testing::TempPath("walk.glb");
  const std::string report = testing::TempPath("walk.json");
  const std::string base = "retarget --quiet --source=" + source + " --target=" + target +
                           " --iterations=3 --max_frames=6 --animation_name=walk --animation_only";
  std::string output;
  ASSERT_EQ(testing::RunCli(base + " --out=" + out + " --report=" + report, &output), 0) << output;
  GltfDocument written, character;
  ASSERT_TRUE(GltfDocument::Read(out, &written).ok());
  ASSERT_TRUE(GltfDocument::Read(target, &character).ok());
  const tinygltf::Model& model = written.model();
  EXPECT_TRUE(model.meshes.empty());
  EXPECT_TRUE(model.images.empty());
  ASSERT_EQ(model.animations.size(), 1u);
  EXPECT_EQ(model.animations[0].name, "walk");
  ASSERT_EQ(model.skins.size(), 1u);
  EXPECT_EQ(model.skins[0].joints.size(), 19u);
  // Every node is one of the character's, by name (what Blender and three.js bind by).
  std::vector<std::string> names;
  for (const tinygltf::Node& node : character.model().nodes) names.push_back(node.name);
  for (const tinygltf::Node& node : model.nodes) {
    EXPECT_NE(std::find(names.begin(), names.end(), node.name), names.end()) << node.name;
  }
  for (const tinygltf::AnimationChannel& channel : model.animations[0].channels) {
    EXPECT_GE(channel.target_node, 0);
  }
  std::ifstream out_file(out, std::ios::binary | std::ios::ate), target_file(target, std::ios::binary | std::ios::ate);
  // RiggedFigure is 50 kB, 6 frames' keys and the nodes' JSON 13 kB.
  EXPECT_LT(static_cast<long>(out_file.tellg()), static_cast<long>(target_file.tellg()) / 2);
  JsonNode root;
  ASSERT_TRUE(ReadJsonFile(report, &root).ok());
  ASSERT_NE(root.Find("animation_only"), nullptr);
  EXPECT_TRUE(root.Find("animation_only")->boolean);
  const JsonNode* options = root.Find("options");
  ASSERT_NE(options, nullptr);
  ASSERT_NE(options->Find("animation_only"), nullptr);
  EXPECT_TRUE(options->Find("animation_only")->boolean);
  // Only for a glTF or FBX --out.
  const std::string bvh = testing::TempPath("walk.bvh");
  EXPECT_EQ(testing::RunCli(base + " --out=" + bvh, &output), 1);
  EXPECT_THAT(output, HasSubstr("--animation_only: applies to a .glb/.gltf/.fbx --out"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  EXPECT_FALSE(testing::FileExists(bvh));
}

TEST(RetargetCli, BadInputsFailWithOneLine) {
  MOCAPSOLVE_DATA_FILE(source, "gltf/CesiumMan.glb");
  MOCAPSOLVE_DATA_FILE(target, "gltf/RiggedFigure.glb");
  const std::string out = testing::TempPath("out.bvh");
  const std::string mask = testing::TempPath("mask.json");
  {
    std::ofstream file(mask);
    file << "{\"position_joints\": [\"no_such_joint\"]}";
  }
  const std::string base = "retarget --quiet --source=" + source + " --target=" + target + " --max_frames=3 ";
  struct Case {
    std::string arguments;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"retarget --source=/nonexistent.glb --target=" + target + " --out=" + out, "nonexistent.glb"},
      {base + "--out=" + out + " --solver=newton", "--solver"},
      {base + "--out=" + out + " --source_animation=Dance", "Dance"},
      {base + "--out=" + out + " --blend_mask=" + mask, "no_such_joint"},
      {base + "--out=" + target, "input"},
      {base + "--out=" + out + " --subsample=0", "--subsample"},
      {base + "--out=" + testing::TempPath("out.obj"), "expected .glb"},
      {"retarget --source=" + source + " --target=" + target, "--out"},
  };
  for (const Case& c : cases) {
    std::string output;
    EXPECT_EQ(testing::RunCli(c.arguments, &output), 1) << c.arguments << "\n" << output;
    EXPECT_THAT(output, HasSubstr(c.message)) << c.arguments;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  }
  EXPECT_FALSE(testing::FileExists(out));
}

TEST(RetargetCli, CmuBvhWalkOntoXbot) {
  MOCAPSOLVE_DATA_FILE(source, "bvh/16_15.bvh");
  MOCAPSOLVE_DATA_FILE(target, "gltf/Xbot.glb");
  const std::string out = testing::TempPath("walk.bvh");
  const std::string report = testing::TempPath("walk.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("retarget --quiet --source=" + source + " --target=" + target + " --out=" + out +
                                " --max_frames=60 --report=" + report,
                            &output),
            0)
      << output;
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadBvh(out, &skeleton, &motion).ok());
  EXPECT_EQ(motion.num_frames(), 60);
  EXPECT_EQ(skeleton.num_joints(), 65);
  JsonNode root;
  ASSERT_TRUE(ReadJsonFile(report, &root).ok());
  ASSERT_NE(root.Find("source_kind"), nullptr);
  EXPECT_EQ(root.Find("source_kind")->string, "skeleton");
  EXPECT_GE(root.Find("mapped_joints")->number, 15);
  EXPECT_LT(root.Find("mean_position_error_fraction_of_height")->number, 0.05);
  EXPECT_LE(root.Find("result_plant_skating_cm_per_s")->number,
            root.Find("source_plant_skating_cm_per_s")->number + 0.5);
}

// Names that match nothing (CesiumMan's) through a joint map file.
TEST(RetargetCli, JointMapFileMapsUnrelatedNames) {
  MOCAPSOLVE_DATA_FILE(cesium, "gltf/CesiumMan.glb");
  MOCAPSOLVE_DATA_FILE(target, "gltf/Xbot.glb");
  const std::string bvh = testing::TempPath("cesium.bvh");
  std::string output;
  ASSERT_EQ(testing::RunCli("convert --quiet " + cesium + " " + bvh, &output), 0) << output;
  const std::string map = testing::TempPath("map.json");
  {
    std::ofstream file(map);
    file << "{\"joints\": {\"Skeleton_torso_joint_1\": \"mixamorig:Hips\", "
            "\"Skeleton_torso_joint_2\": \"mixamorig:Spine1\", \"torso_joint_3\": \"mixamorig:Spine2\", "
            "\"Skeleton_neck_joint_2\": \"mixamorig:Head\", "
            "\"leg_joint_L_1\": \"mixamorig:LeftUpLeg\", \"leg_joint_L_2\": \"mixamorig:LeftLeg\", "
            "\"leg_joint_L_3\": \"mixamorig:LeftFoot\", \"leg_joint_R_1\": \"mixamorig:RightUpLeg\", "
            "\"leg_joint_R_2\": \"mixamorig:RightLeg\", \"leg_joint_R_3\": \"mixamorig:RightFoot\"}}";
  }
  const std::string out = testing::TempPath("out.bvh");
  const std::string report = testing::TempPath("report.json");
  const std::string base = "retarget --quiet --source=" + bvh + " --target=" + target + " --max_frames=10 --out=" + out;
  // Without the map: no name matches; the humanoid roles found by structure map them.
  ASSERT_EQ(testing::RunCli(base + " --report=" + report, &output), 0) << output;
  JsonNode root;
  ASSERT_TRUE(ReadJsonFile(report, &root).ok());
  EXPECT_GE(root.Find("mapped_joints")->number, 17);
  const JsonNode* roles = root.Find("joint_map_roles");
  ASSERT_NE(roles, nullptr);
  EXPECT_EQ(roles->Find("left_thigh")->Find("source")->string, "leg_joint_L_1");
  EXPECT_EQ(roles->Find("left_thigh")->Find("target")->string, "mixamorig:LeftUpLeg");
  EXPECT_EQ(roles->Find("left_thigh")->Find("how")->string, "structure");
  EXPECT_EQ(roles->Find("right_forearm")->Find("target")->string, "mixamorig:RightForeArm");
  EXPECT_GT(root.Find("joint_map_confidence")->number, 0.6);  // Sides from the names _L/_R: x 0.75.
  EXPECT_LT(root.Find("mean_position_error_fraction_of_height")->number, 0.05);
  // The file overrides: its pairs are decided by "file".
  ASSERT_EQ(testing::RunCli(base + " --joint_map=" + map + " --report=" + report, &output), 0) << output;
  ASSERT_TRUE(ReadJsonFile(report, &root).ok());
  EXPECT_EQ(root.Find("joint_map_roles")->Find("left_thigh")->Find("how")->string, "file");
  EXPECT_EQ(root.Find("joint_map")->Find("Skeleton_torso_joint_2")->string, "mixamorig:Spine1");
  EXPECT_LT(root.Find("mean_position_error_fraction_of_height")->number, 0.05);
}

// `joint_map` prints the automatic map as JSON that --joint_map reads back; a map naming a
// joint that does not exist names it and its side.
TEST(RetargetCli, JointMapCommandPrintsAMapRetargetReadsBack) {
  MOCAPSOLVE_DATA_FILE(cesium, "gltf/CesiumMan.glb");
  MOCAPSOLVE_DATA_FILE(target, "gltf/Xbot.glb");
  const std::string bvh = testing::TempPath("cesium.bvh");
  std::string output;
  ASSERT_EQ(testing::RunCli("convert --quiet " + cesium + " " + bvh, &output), 0) << output;
  const std::string map = testing::TempPath("map.json");
  ASSERT_EQ(testing::RunCli("joint_map --source=" + bvh + " --target=" + target + " --out=" + map, &output), 0)
      << output;
  JsonNode printed;
  ASSERT_TRUE(ReadJsonFile(map, &printed).ok());
  EXPECT_EQ(printed.Find("roles")->Find("left_shin")->Find("source")->string, "leg_joint_L_2");
  EXPECT_EQ(printed.Find("roles")->Find("left_shin")->Find("target")->string, "mixamorig:LeftLeg");
  EXPECT_EQ(printed.Find("joints")->Find("leg_joint_R_3")->string, "mixamorig:RightFoot");
  const std::string report = testing::TempPath("report.json");
  const std::string out = testing::TempPath("out.bvh");
  ASSERT_EQ(testing::RunCli("retarget --quiet --source=" + bvh + " --target=" + target + " --max_frames=5 --out=" + out +
                                " --joint_map=" + map + " --report=" + report, &output), 0) << output;
  JsonNode root;
  ASSERT_TRUE(ReadJsonFile(report, &root).ok());
  EXPECT_EQ(root.Find("joint_map_roles")->Find("left_shin")->Find("how")->string, "file");
  EXPECT_EQ(root.Find("mapped_joints")->number, static_cast<double>(printed.Find("joints")->members.size()));

  const std::string bad_source = testing::TempPath("bad_source.json");
  const std::string bad_target = testing::TempPath("bad_target.json");
  std::ofstream(bad_source) << "{\"roles\": {\"left_shin\": {\"source\": \"NoSuchShin\", \"target\": \"mixamorig:LeftLeg\"}}}";
  std::ofstream(bad_target) << "{\"roles\": {\"left_shin\": {\"source\": \"leg_joint_L_2\", \"target\": \"NoSuchLeg\"}}}";
  for (const auto& [file, message] : {std::make_pair(bad_source, "the source skeleton has no joint 'NoSuchShin'"),
                                      std::make_pair(bad_target, "the target skeleton has no joint 'NoSuchLeg'")}) {
    const std::string second = testing::TempPath("second.json");
    EXPECT_EQ(testing::RunCli("joint_map --source=" + bvh + " --target=" + target + " --joint_map=" + file +
                                  " --out=" + second, &output), 1);
    EXPECT_THAT(output, HasSubstr(message));
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
    EXPECT_FALSE(testing::FileExists(second));
  }
}

TEST(RetargetCli, SkeletonSourceBadInputsFailWithOneLine) {
  MOCAPSOLVE_DATA_FILE(source, "bvh/16_15.bvh");
  MOCAPSOLVE_DATA_FILE(target, "gltf/Xbot.glb");
  MOCAPSOLVE_DATA_FILE(fox, "gltf/Fox.glb");  // A quadruped: no humanoid roles, no names in common.
  const std::string out = testing::TempPath("out.glb");
  const std::string unknown = testing::TempPath("unknown.json");
  const std::string unknown_source = testing::TempPath("unknown_source.json");
  const std::string cycle = testing::TempPath("cycle.gltf");
  const std::string skinless = testing::TempPath("skinless.gltf");
  {
    std::ofstream(unknown) << "{\"joints\": {\"lfemur\": \"mixamorig:NoSuchLeg\"}}";
    std::ofstream(unknown_source) << "{\"joints\": {\"NoSuchThigh\": \"mixamorig:LeftUpLeg\"}}";
    // Two joints, each the other's child: a cycle (glTF forbids it; the reader must say so).
    std::ofstream(cycle) << "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [{\"name\": \"a\", \"children\": [1]}, "
                            "{\"name\": \"b\", \"children\": [0]}], \"skins\": [{\"joints\": [0, 1]}], "
                            "\"scenes\": [{\"nodes\": [0]}]}";
    std::ofstream(skinless) << "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [{\"name\": \"a\"}], "
                               "\"scenes\": [{\"nodes\": [0]}]}";
  }
  const std::string base = "retarget --quiet --source=" + source + " --max_frames=3 --out=" + out + " ";
  struct Case {
    std::string arguments;
    std::string message;
  };
  const std::vector<Case> cases = {
      {base + "--target=" + skinless, "has no skin"},
      {base + "--target=" + target + " --joint_map=" + unknown, "target skeleton has no joint 'mixamorig:NoSuchLeg'"},
      {base + "--target=" + target + " --joint_map=" + unknown_source, "source skeleton has no joint 'NoSuchThigh'"},
      {base + "--target=" + cycle, "cycle.gltf: node 0 'a': is in a cycle"},
      {base + "--target=" + target + " --joint_map=" + testing::TempPath("missing.json"), "missing.json"},
      {base + "--target=" + target + " --foot_joints=NoFoot", "NoFoot"},
      {"retarget --quiet --source=" + fox + " --source_mesh=false --max_frames=3 --out=" + out + " --target=" + target,
       "too different to map (0 joints map, need 5): source: not a humanoid ("},
  };
  for (const Case& c : cases) {
    std::string output;
    EXPECT_EQ(testing::RunCli(c.arguments, &output), 1) << c.arguments << "\n" << output;
    EXPECT_THAT(output, HasSubstr(c.message)) << c.arguments;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  }
  EXPECT_FALSE(testing::FileExists(out));
  std::string output;  // The refusal lists what each side was found to be.
  testing::RunCli(cases.back().arguments, &output);
  EXPECT_THAT(output, HasSubstr("target: humanoid (roles: pelvis, spine_1"));
}

TEST(RetargetCli, RootMotionModes) {
  MOCAPSOLVE_DATA_FILE(robot, "gltf/RobotExpressive.glb");
  MOCAPSOLVE_DATA_FILE(xbot, "gltf/Xbot.glb");
  MOCAPSOLVE_DATA_FILE(walk, "bvh/16_15.bvh");
  const std::string bvh = testing::TempPath("robot_running.bvh");
  std::string output;
  ASSERT_EQ(testing::RunCli("convert --quiet " + robot + " " + bvh + " --animation=Running", &output), 0) << output;
  const std::string report = testing::TempPath("robot_root_bone.json");
  const std::string out = testing::TempPath("robot_root_bone.bvh");
  ASSERT_EQ(testing::RunCli("retarget --quiet --source=" + bvh + " --target=" + robot + " --root_motion=root_bone --out=" +
                                out + " --report=" + report,
                            &output),
            0)
      << output;
  JsonNode root;
  ASSERT_TRUE(ReadJsonFile(report, &root).ok());
  bool noted = false;
  for (const JsonNode& note : root.Find("notes")->items) {
    noted |= note.string.find("root motion root_bone: the track of 'Body'") != std::string::npos &&
             note.string.find("carried by the root bone 'Bone'") != std::string::npos;
  }
  EXPECT_TRUE(noted);
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadBvh(out, &skeleton, &motion).ok());
  // The root bone 'Bone' moves with the run (the clip itself runs on the spot: the track is short).
  ASSERT_EQ(skeleton.name(0), "Bone");
  const std::string xbot_out = testing::TempPath("xbot_root_bone.bvh");
  EXPECT_EQ(testing::RunCli("retarget --quiet --source=" + walk + " --target=" + xbot + " --max_frames=5 "
                            "--root_motion=root_bone --out=" + xbot_out, &output), 1);
  EXPECT_THAT(output, HasSubstr("no root bone above its hips ('mixamorig:Hips'"));
  EXPECT_FALSE(testing::FileExists(xbot_out));
  EXPECT_EQ(testing::RunCli("retarget --quiet --source=" + walk + " --target=" + xbot + " --max_frames=5 "
                            "--root_motion=engine --out=" + xbot_out, &output), 1);
  EXPECT_THAT(output, HasSubstr("root_motion"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  EXPECT_EQ(testing::RunCli("retarget --quiet --source=" + walk + " --target=" + xbot + " --max_frames=5 "
                            "--root_motion=in_place --out=" + xbot_out, &output), 0) << output;
  // --stride=legs: RobotExpressive's legs are a smaller share of its height than the CMU actor's
  // (0.902 along its bones, its IK feet on the shins in the solve; 0.808 while the rest alignment
  // tilted the actor's pelvis by the robot's, the bound mesh then shorter: height ratio 0.0228
  // against 0.0204 upright; 0.759 hip to IK foot before that).
  const std::string stride_report = testing::TempPath("robot_stride.json");
  ASSERT_EQ(testing::RunCli("retarget --quiet --source=" + walk + " --target=" + robot + " --max_frames=5 "
                            "--stride=legs --out=" + testing::TempPath("robot_stride.bvh") + " --report=" + stride_report,
                            &output), 0) << output;
  ASSERT_TRUE(ReadJsonFile(stride_report, &root).ok());
  bool scaled = false;
  for (const JsonNode& note : root.Find("notes")->items) {
    scaled |= note.string.find("stride scaled by the leg-length ratio: 0.90") != std::string::npos;
  }
  EXPECT_TRUE(scaled);
}

}  // namespace
}  // namespace mocapsolve
