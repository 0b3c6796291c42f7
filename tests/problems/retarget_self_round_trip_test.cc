// The self round trip of issue 29 item 1 on every shared glTF character (skipped without
// the data): the character's first animation, written as BVH (what `mocapsolve convert`
// writes) and retargeted back onto the same character with the default settings (what
// `mocapsolve retarget --source=that.bvh --target=the.glb` runs, through RunRetarget),
// must give back the clip: every joint's world position at every frame within 0.1 % of
// the character's height (the bind-pose mesh's vertical extent). The figures are printed
// (one line per character and a JSON line), so the test is also the measurement.
#include <algorithm>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "io/bvh_writer.h"
#include "io/gltf_reader.h"
#include "kinematics/forward_kinematics.h"
#include "problems/retarget/mesh_mapping.h"
#include "problems/retarget/retarget_setup.h"
#include "tasks/retarget_task.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

class SelfRoundTripTest : public ::testing::TestWithParam<const char*> {};

TEST_P(SelfRoundTripTest, JointsWithinOneThousandthOfTheHeight) {
  const std::string name = GetParam();
  MOCAPSOLVE_DATA_FILE(path, "gltf/" + name + ".glb");
  GltfDocument document;
  ASSERT_TRUE(GltfDocument::Read(path, &document).ok());
  GltfCharacter character;
  ASSERT_TRUE(ReadGltfCharacter(document, GltfReadOptions(), &character).ok());
  Motion clip;
  ASSERT_TRUE(ReadGltfAnimation(document, character, GltfAnimationOptions(), &clip).ok());
  const std::string bvh = testing::TempPath(name + ".bvh");
  ASSERT_TRUE(WriteBvh(bvh, character.skeleton, clip).ok());

  // The character's height: its bind-pose mesh in its world (as the retarget measures it).
  Eigen::Matrix3Xd rest;
  const Pose bind = character.bind_pose.rotations.empty() ? RestPose(character.skeleton) : character.bind_pose;
  BindPoseMesh(character.mesh, WorldFromBindRotation(character.skeleton, bind, character.rest_pose), &rest, nullptr);
  const double height = ComputeCharacterFrame(rest).height;
  ASSERT_GT(height, 0.0);

  RetargetInputs inputs;
  inputs.source = bvh;
  inputs.target = path;
  RetargetTaskResult task;
  const Status status = RunRetarget(inputs, RetargetConfig(), nullptr, &task);
  ASSERT_TRUE(status.ok()) << name << ": " << status.message();
  const Motion& result = task.retarget.clip.motion;
  ASSERT_EQ(result.num_frames(), clip.num_frames());
  const std::vector<Vector3dVector> truth = ClipJointPositions(character.skeleton, clip);
  const std::vector<Vector3dVector> got = ClipJointPositions(character.skeleton, result);
  double worst = 0.0;
  int worst_frame = 0, worst_joint = 0;
  for (int f = 0; f < clip.num_frames(); ++f) {
    for (int j = 0; j < character.skeleton.num_joints(); ++j) {
      const double error = (truth[f][j] - got[f][j]).norm() / height;
      if (error > worst) {
        worst = error;
        worst_frame = f;
        worst_joint = j;
      }
    }
  }
  std::printf("self round trip %-16s %4d frames %3d joints: max joint error %.5f %% of height %.4g "
              "(frame %d, %s)\n",
              name.c_str(), clip.num_frames(), character.skeleton.num_joints(), 100.0 * worst, height,
              worst_frame, character.skeleton.name(worst_joint).c_str());
  std::printf("{\"self_round_trip\": \"%s\", \"frames\": %d, \"max_joint_error_percent_of_height\": %.6g}\n",
              name.c_str(), clip.num_frames(), 100.0 * worst);
  for (const std::string& note : task.retarget.notes) std::printf("  note: %s\n", note.c_str());
  EXPECT_LE(worst, 1e-3) << name << ": worst at frame " << worst_frame << ", joint "
                         << character.skeleton.name(worst_joint);
}

INSTANTIATE_TEST_SUITE_P(SharedCharacters, SelfRoundTripTest,
                         ::testing::Values("Xbot", "Soldier", "CesiumMan", "Ely", "RiggedFigure",
                                           "RobotExpressive", "Fox"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

}  // namespace
}  // namespace mocapsolve
