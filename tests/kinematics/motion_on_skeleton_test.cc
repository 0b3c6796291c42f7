// MotionOnSkeleton: a BVH written from a skeleton with rest rotations (the writer folds
// them into the angles) read back and moved onto the original skeleton gives the same
// forward kinematics; drawn on the original without the move it does not (the view of a
// solve's BVH over an ASF subject, lying on its side). Another skeleton is an error.
#include "kinematics/motion_on_skeleton.h"

#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/bvh_reader.h"
#include "io/bvh_writer.h"
#include "kinematics/forward_kinematics.h"
#include "tests/kinematics/test_rigs.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

double LargestJointDistance(const Skeleton& a, const Motion& ma, const Skeleton& b, const Motion& mb) {
  const std::vector<Vector3dVector> pa = ClipJointPositions(a, ma), pb = ClipJointPositions(b, mb);
  double largest = 0.0;
  for (size_t f = 0; f < pa.size(); ++f) {
    for (size_t j = 0; j < pa[f].size(); ++j) largest = std::max(largest, (pa[f][j] - pb[f][j]).norm());
  }
  return largest;
}

class MotionOnSkeletonTest : public ::testing::Test {
 protected:
  void SetUp() override {
    skeleton_ = testing::MakeTestSkeleton();
    std::mt19937 rng(7);
    motion_.frame_rate = 30.0;
    for (int f = 0; f < 6; ++f) motion_.frames.push_back(testing::RandomPose(skeleton_, &rng));
    const std::string path = testing::TempPath("rest_rotations.bvh");
    BvhWriteOptions options;
    options.precision = 12;
    ASSERT_TRUE(WriteBvh(path, skeleton_, motion_, options).ok());
    ASSERT_TRUE(ReadBvh(path, &file_skeleton_, &file_motion_).ok());
  }
  Skeleton skeleton_, file_skeleton_;
  Motion motion_, file_motion_;
};

TEST_F(MotionOnSkeletonTest, SameForwardKinematicsOnTheOriginalSkeleton) {
  // The file's angles include the rest rotations: on the original skeleton they are
  // applied twice (what `view` drew before).
  EXPECT_GT(LargestJointDistance(skeleton_, motion_, skeleton_, file_motion_), 0.1);
  Motion moved;
  const Status status = MotionOnSkeleton(file_skeleton_, file_motion_, skeleton_, &moved);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(moved.num_frames(), motion_.num_frames());
  EXPECT_EQ(moved.frame_rate, 30.0);
  EXPECT_LT(LargestJointDistance(skeleton_, motion_, skeleton_, moved), 1e-9);  // 12 digits written.
  // In place, and the identity onto its own skeleton.
  Motion same = file_motion_;
  ASSERT_TRUE(MotionOnSkeleton(file_skeleton_, same, file_skeleton_, &same).ok());
  EXPECT_LT(LargestJointDistance(file_skeleton_, file_motion_, file_skeleton_, same), 1e-12);
}

TEST_F(MotionOnSkeletonTest, AnotherSkeletonIsAnError) {
  std::vector<JointSpec> joints;
  for (int j = 0; j < skeleton_.num_joints(); ++j) joints.push_back(skeleton_.joint(j));
  joints[4].offset *= 1.1;
  Skeleton longer;
  ASSERT_TRUE(Skeleton::Create(joints, skeleton_.end_sites(), skeleton_.unit(), &longer).ok());
  Motion moved;
  Status status = MotionOnSkeleton(file_skeleton_, file_motion_, longer, &moved);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("joint 4 'head': offset differs"));

  joints = {};
  for (int j = 0; j < skeleton_.num_joints(); ++j) joints.push_back(skeleton_.joint(j));
  joints[6].name = "left_hand";
  Skeleton renamed;
  ASSERT_TRUE(Skeleton::Create(joints, skeleton_.end_sites(), skeleton_.unit(), &renamed).ok());
  status = MotionOnSkeleton(file_skeleton_, file_motion_, renamed, &moved);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("joint 6 'left_hand' is 'l_hand' in the motion"));

  Skeleton fewer;
  ASSERT_TRUE(Skeleton::Create({skeleton_.joint(0)}, {}, skeleton_.unit(), &fewer).ok());
  status = MotionOnSkeleton(file_skeleton_, file_motion_, fewer, &moved);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("joints"));
}

}  // namespace
}  // namespace mocapsolve
