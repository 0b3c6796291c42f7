// The CLI on glTF and FBX input: info, convert to BVH (FK of the BVH equals FK of the
// source), fk, and --animation selection.
#include <string>

#include <gtest/gtest.h>

#include "io/bvh_reader.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
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

}  // namespace
}  // namespace mocapsolve
