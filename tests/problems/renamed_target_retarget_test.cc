// A CMU BVH retargeted onto Xbot and onto Xbot with every joint renamed to a random name
// (in memory; same mesh, bind and rest poses): the structural joint map must make the two
// results agree: the same joint pairs, and every joint within 0.1 mm at every frame (the
// largest distance is printed: the measurement). Skipped without MOCAPSOLVE_DATA.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/gltf_reader.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
#include "problems/retarget/retarget_character.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

TEST(RenamedTargetRetargetTest, CmuWalkOntoXbotWithRandomNamesMatchesTheOriginalNames) {
  MOCAPSOLVE_DATA_FILE(bvh, "bvh/131_02.bvh");
  MOCAPSOLVE_DATA_FILE(glb, "gltf/Xbot.glb");
  Skeleton source;
  Motion motion;
  ASSERT_TRUE(ReadMotionFile(bvh, MotionFileOptions(), &source, &motion).ok());
  motion.frames.resize(std::min<size_t>(motion.frames.size(), 40));
  GltfCharacter xbot;
  ASSERT_TRUE(ReadGltfCharacter(glb, GltfReadOptions(), &xbot).ok());
  std::vector<JointSpec> specs;
  for (int j = 0; j < xbot.skeleton.num_joints(); ++j) {
    specs.push_back(xbot.skeleton.joint(j));
    specs.back().name = "j" + std::to_string(90000 - 37 * j);
  }
  Skeleton renamed;
  ASSERT_TRUE(Skeleton::Create(specs, {}, xbot.skeleton.unit(), &renamed).ok());

  auto run = [&](const Skeleton& target_skeleton, CharacterRetargetResult* result) {
    RetargetCharacter source_view, target_view;
    source_view.skeleton = &source;
    target_view.skeleton = &target_skeleton;
    target_view.mesh = &xbot.mesh;
    target_view.bind_pose = xbot.bind_pose;
    target_view.rest_pose = xbot.rest_pose;
    const Status status = RetargetMotionOntoCharacter(source_view, motion, target_view, CharacterRetargetOptions(), result);
    ASSERT_TRUE(status.ok()) << status.message();
  };
  CharacterRetargetResult named, random;
  run(xbot.skeleton, &named);
  run(renamed, &random);
  for (int j = 0; j < source.num_joints(); ++j) {
    const int x = named.joint_map.target_of_source[j], y = random.joint_map.target_of_source[j];
    if (x != y) {
      ADD_FAILURE() << source.name(j) << " -> " << (x >= 0 ? xbot.skeleton.name(x) : "-") << " by names, "
                    << (y >= 0 ? xbot.skeleton.name(y) : "-") << " renamed (" << random.joint_map.how_of_source[j] << ")";
    }
  }
  const std::vector<Vector3dVector> a = ClipJointPositions(xbot.skeleton, named.clip.motion);
  const std::vector<Vector3dVector> b = ClipJointPositions(renamed, random.clip.motion);
  std::vector<bool> role(xbot.skeleton.num_joints(), false);
  for (const auto& [name, joint] : random.joint_map.target_roles.roles) role[joint] = true;
  double worst_role = 0.0, worst_any = 0.0;
  for (size_t f = 0; f < a.size(); ++f) {
    for (int j = 0; j < xbot.skeleton.num_joints(); ++j) {
      const double d = (a[f][j] - b[f][j]).norm();
      worst_any = std::max(worst_any, d);
      if (role[j]) worst_role = std::max(worst_role, d);
    }
  }
  std::printf("131_02 onto Xbot vs renamed Xbot (%zu frames): mapped %d vs %d joints; max joint distance at "
              "role joints %.4f mm, at any joint %.4f mm\n",
              a.size(), named.joint_map.num_mapped(), random.joint_map.num_mapped(), 1e3 * worst_role, 1e3 * worst_any);
  EXPECT_LT(worst_role, 1e-4);
  EXPECT_LT(worst_any, 1e-4);
}

}  // namespace
}  // namespace mocapsolve
