#include "kinematics/forward_kinematics.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "tests/kinematics/test_rigs.h"

namespace mocapsolve {
namespace {

// Reference: the DESIGN.md product of 4x4 transforms, world_from_joint_j =
// world_from_joint_parent * T(t_j) * R_rest_j * R_j, computed naively.
std::vector<Eigen::Isometry3d> NaiveTransforms(const Skeleton& s, const Pose& pose) {
  std::vector<Eigen::Isometry3d> world(s.num_joints());
  for (int j = 0; j < s.num_joints(); ++j) {
    Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
    local.translate(pose.translations[j]);
    local.rotate(s.rest_rotation(j) * pose.rotations[j]);
    world[j] = s.parent(j) < 0 ? local : world[s.parent(j)] * local;
  }
  return world;
}

TEST(ForwardKinematics, MatchesNaiveTransformProduct) {
  const Skeleton s = testing::MakeTestSkeleton();
  std::mt19937 rng(1);
  FkData data(s);
  for (int trial = 0; trial < 20; ++trial) {
    const Pose pose = testing::RandomPose(s, &rng);
    ForwardKinematics(s, pose, &data);
    const auto naive = NaiveTransforms(s, pose);
    for (int j = 0; j < s.num_joints(); ++j) {
      // Both are a handful of products of unit quaternions: round-off only.
      EXPECT_LT((data.world_positions[j] - naive[j].translation()).norm(), 1e-14);
      EXPECT_TRUE(data.world_rotations[j].toRotationMatrix().isApprox(naive[j].linear(), 1e-14));
    }
  }
}

TEST(ForwardKinematics, HandComputedChain) {
  // Two joints: root at (1,0,0) rotated 90 deg about z; child offset (2,0,0).
  JointSpec root{"root", -1, {1, 0, 0}, Eigen::Quaterniond::Identity(), {}, std::nullopt, {}};
  JointSpec child{"child", 0, {2, 0, 0}, Eigen::Quaterniond::Identity(), {}, std::nullopt, {}};
  Skeleton s;
  ASSERT_TRUE(Skeleton::Create({root, child}, {{"child_End", 1, {0, 1, 0}}}, Metres(), &s).ok());
  Pose pose = RestPose(s);
  pose.rotations[0] = Eigen::Quaterniond(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()));
  pose.rotations[1] = Eigen::Quaterniond(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()));
  FkData data(s);
  ForwardKinematics(s, pose, &data);
  EXPECT_LT((data.world_positions[0] - Eigen::Vector3d(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((data.world_positions[1] - Eigen::Vector3d(1, 2, 0)).norm(), 1e-15);
  // End site (0,1,0) in a frame turned 180 deg: points along -y.
  EXPECT_LT((EndSitePositions(s, data)[0] - Eigen::Vector3d(1, 1, 0)).norm(), 1e-15);
}

TEST(ForwardKinematics, ClipPositionsPerFrame) {
  const Skeleton s = testing::MakeTestSkeleton();
  std::mt19937 rng(2);
  Motion motion;
  motion.frame_rate = 30;
  for (int f = 0; f < 5; ++f) motion.frames.push_back(testing::RandomPose(s, &rng));
  const auto clip = ClipJointPositions(s, motion);
  ASSERT_EQ(clip.size(), 5u);
  FkData data(s);
  ForwardKinematics(s, motion.frames[3], &data);
  for (int j = 0; j < s.num_joints(); ++j) EXPECT_EQ(clip[3][j], data.world_positions[j]);
  EXPECT_TRUE(ValidateMotion(s, motion).ok());
  motion.frames[2].rotations[4].coeffs() *= 2.0;
  const Status status = ValidateMotion(s, motion);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("frame 2"), std::string::npos);
  EXPECT_NE(status.message().find("head"), std::string::npos);
}

// ValidatePose (what ValidateMotion checks per frame): joint count, then finite unit values.
TEST(ValidatePose, NamesTheJointCountOrTheBadJoint) {
  const Skeleton s = testing::MakeTestSkeleton();
  std::mt19937 rng(3);
  Pose pose = testing::RandomPose(s, &rng);
  EXPECT_TRUE(ValidatePose(s, pose, "pose").ok());
  Pose short_pose = pose;
  short_pose.rotations.pop_back();
  short_pose.translations.pop_back();
  Status status = ValidatePose(s, short_pose, "pose");
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("joint count"), std::string::npos) << status.message();
  pose.translations[1].x() = std::nan("");
  status = ValidatePose(s, pose, "pose");
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().rfind("pose, joint '", 0), 0u) << status.message();
}

}  // namespace
}  // namespace mocapsolve
