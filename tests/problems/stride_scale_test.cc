// Stride length by the leg-length ratio (problems/retarget/stride_scale.h): the leg length
// along the bones and, for a foot that is an IK bone under a root bone, in the rest pose;
// the root's horizontal path scaled about its first frame, the vertical kept.
#include "problems/retarget/stride_scale.h"

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// Root -> Hips -> Thigh -> Shin (0.4) -> Foot (0.45); an IK foot under the root at the ankle.
Skeleton MakeLeg() {
  std::vector<JointSpec> specs(6);
  const char* names[] = {"Root", "Hips", "Thigh", "Shin", "Foot", "FootIK"};
  const int parents[] = {-1, 0, 1, 2, 3, 0};
  const Eigen::Vector3d offsets[] = {{0, 0, 0},    {0, 0.95, 0},   {0.1, -0.05, 0},
                                     {0, -0.4, 0}, {0, -0.3, 0.3}, {0.1, 0.1, 0}};
  for (int j = 0; j < 6; ++j) specs[j].name = names[j], specs[j].parent = parents[j], specs[j].offset = offsets[j];
  Skeleton skeleton;
  EXPECT_TRUE(Skeleton::Create(specs, {}, Metres(), &skeleton).ok());
  return skeleton;
}

TEST(StrideScaleTest, LegLengthAlongTheBonesOrInTheRestPose) {
  const Skeleton leg = MakeLeg();
  EXPECT_NEAR(LegLength(leg, {{2, 4}}), 0.4 + std::sqrt(0.18), 1e-12);
  // The IK foot: thigh at (0.1, 0.9, 0), IK foot at (0.1, 0.1, 0).
  EXPECT_NEAR(LegLength(leg, {{2, 5}}), 0.8, 1e-12);
  EXPECT_NEAR(LegLength(leg, {{2, 4}, {2, 5}}), (0.4 + std::sqrt(0.18) + 0.8) / 2, 1e-12);
  EXPECT_EQ(LegLength(leg, {{2, -1}, {-1, 4}}), 0.0);
}

TEST(StrideScaleTest, ScalesTheRootsHorizontalPathAboutTheFirstFrame) {
  Motion motion;
  for (int f = 0; f < 3; ++f) {
    Pose pose;
    pose.translations = {Eigen::Vector3d(1 + f, 0.9 + 0.1 * f, 2 - f), Eigen::Vector3d(0, 1, 0)};
    pose.rotations.assign(2, Eigen::Quaterniond::Identity());
    motion.frames.push_back(pose);
  }
  ScaleRootStride(0.5, &motion);
  EXPECT_TRUE(motion.frames[0].translations[0].isApprox(Eigen::Vector3d(1, 0.9, 2)));
  EXPECT_TRUE(motion.frames[2].translations[0].isApprox(Eigen::Vector3d(2, 1.1, 1)));
  EXPECT_TRUE(motion.frames[2].translations[1].isApprox(Eigen::Vector3d(0, 1, 0)));
}

}  // namespace
}  // namespace mocapsolve
