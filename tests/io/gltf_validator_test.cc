// The Khronos glTF-Validator on a file the writer produced (scripts/validate_gltf.sh).
// Skips when node is missing or the validator cannot be installed (exit 77).
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

TEST(GltfValidator, WrittenFilesHaveNoErrors) {
  if (std::system("command -v node >/dev/null 2>&1") != 0) GTEST_SKIP() << "node not found";
  MOCAPSOLVE_DATA_FILE(path, "gltf/CesiumMan.glb");
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Read(path, &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  Motion motion;
  ASSERT_TRUE(ReadGltfAnimation(doc, c, {}, &motion).ok());
  for (int f = 0; f < motion.num_frames(); ++f) {  // A clip the file does not hold.
    for (int j = 0; j < c.skeleton.num_joints(); ++j) {
      motion.frames[f].rotations[j] =
          motion.frames[f].rotations[j] * ExpMap(Eigen::Vector3d(0.2 * std::sin(0.2 * f + j), 0.0, 0.1));
    }
  }
  const std::string glb = testing::TempPath("validated.glb");
  const std::string gltf = testing::TempPath("validated.gltf");
  ASSERT_TRUE(WriteGltfWithAnimation(doc, c, motion, "validated", glb).ok());
  ASSERT_TRUE(WriteGltfWithAnimation(doc, c, motion, "validated", gltf).ok());
  // The viewer pages' variant: rotations as normalized int16, a constant channel as one
  // key (the last joint held still).
  for (Pose& pose : motion.frames) pose.rotations.back() = Eigen::Quaterniond::Identity();
  const std::string quantized = testing::TempPath("validated_int16.glb");
  std::string bytes;
  GltfWriteOptions compact;
  compact.compact = true;
  ASSERT_TRUE(SerializeGltfWithAnimation(doc, c, motion, "validated", true, &bytes, compact).ok());
  ASSERT_TRUE(WriteFileAtomically(quantized, bytes).ok());
  // --animation_only: skeleton, skin and the animation, no meshes (the skin is unused: an info).
  const std::string animation_only = testing::TempPath("validated_animation_only.glb");
  const std::string animation_only_gltf = testing::TempPath("validated_animation_only.gltf");
  GltfWriteOptions slim;
  slim.animation_only = true;
  ASSERT_TRUE(WriteGltfWithAnimation(doc, c, motion, "validated", animation_only, slim).ok());
  ASSERT_TRUE(WriteGltfWithAnimation(doc, c, motion, "validated", animation_only_gltf, slim).ok());
  const std::string log = testing::TempPath("validator.log");
  const std::string command = testing::SourcePath("scripts/validate_gltf.sh") + " " + glb + " " + gltf + " " +
                              quantized + " " + animation_only + " " + animation_only_gltf + " > " + log + " 2>&1";
  const int raw = std::system(command.c_str());
  const int code = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  const std::string output = testing::ReadTextFile(log);
  std::printf("%s", output.c_str());
  if (code == 77) GTEST_SKIP() << "glTF validator unavailable: " << output;
  EXPECT_EQ(code, 0) << output;
  EXPECT_NE(output.find("validated.glb: 0 errors"), std::string::npos) << output;
  EXPECT_NE(output.find("validated.gltf: 0 errors"), std::string::npos) << output;
  EXPECT_NE(output.find("validated_int16.glb: 0 errors"), std::string::npos) << output;
  EXPECT_NE(output.find("validated_animation_only.glb: 0 errors, 0 warnings"), std::string::npos) << output;
  EXPECT_NE(output.find("validated_animation_only.gltf: 0 errors, 0 warnings"), std::string::npos) << output;
}

}  // namespace
}  // namespace mocapsolve
