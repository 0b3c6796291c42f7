// Tests of problems/marker_solve/locked_axes.h.
#include "problems/marker_solve/locked_axes.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

// The demo character with two-dof feet and shoulders and one-dof toes (an ASF's layout).
Skeleton TwoDofFeetAndShoulders() {
  const Skeleton demo = MakeDemoSkeleton();
  std::vector<JointSpec> joints;
  for (int j = 0; j < demo.num_joints(); ++j) {
    joints.push_back(demo.joint(j));
    const std::string& name = demo.name(j);
    if (name == "LeftFoot" || name == "RightFoot" || name == "LeftShoulder") {
      joints.back().rotation_axes = std::vector<int>{2, 0};
      joints.back().channels = {Channel::kZrotation, Channel::kXrotation};
      joints.back().rotation_limits = {{-1.0, 1.0}, {-0.5, 0.5}};
    }
    if (name == "LeftToe" || name == "RightToe") joints.back().rotation_axes = std::vector<int>{0};
  }
  Skeleton skeleton;
  EXPECT_TRUE(Skeleton::Create(joints, demo.end_sites(), demo.unit(), &skeleton).ok());
  return skeleton;
}

// The feet are candidates; the shoulder is not (the arm's ball joint below makes its axis
// up), nor a foot with fewer than three markers on or below it.
TEST(LockedAxes, AFootIsACandidateAShoulderAboveABallJointIsNot) {
  const Skeleton skeleton = TwoDofFeetAndShoulders();
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, 5);  // The right foot has no toe: 3.
  const std::vector<int> joints = LockedAxisJoints(skeleton, markers);
  ASSERT_EQ(joints.size(), 2u);
  EXPECT_EQ(skeleton.name(joints[0]), "LeftFoot");
  EXPECT_EQ(skeleton.name(joints[1]), "RightFoot");
  const std::vector<int> four = LockedAxisJoints(skeleton, markers, 4);
  ASSERT_EQ(four.size(), 1u);
  EXPECT_EQ(skeleton.name(four[0]), "LeftFoot");
}

// The missing axis goes between the two (z, x) -> (z, y, x) with its channel and an
// unlimited range; at a zero middle angle FK is the two-dof joint's.
TEST(LockedAxes, TheFreedAxisSitsBetweenTheTwoAndChangesNothingAtZero) {
  const Skeleton skeleton = TwoDofFeetAndShoulders();
  const int foot = skeleton.FindJoint("LeftFoot");
  Skeleton freed;
  ASSERT_TRUE(FreeLockedAxes(skeleton, {foot}, &freed).ok());
  EXPECT_EQ(freed.rotation_axes(foot), (std::vector<int>{2, 1, 0}));
  ASSERT_EQ(freed.rotation_limits(foot).size(), 3u);
  EXPECT_TRUE(std::isinf(freed.rotation_limits(foot)[1].second));
  EXPECT_EQ(freed.rotation_limits(foot)[2].second, 0.5);
  EXPECT_EQ(freed.joint(foot).channels.back(), Channel::kYrotation);
  EXPECT_EQ(freed.num_rotation_dofs(skeleton.FindJoint("RightFoot")), 2);
  Pose pose = RestPose(skeleton);
  pose.rotations[foot] = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                                            Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));
  FkData a(skeleton), b(freed);
  ForwardKinematics(skeleton, pose, &a);
  ForwardKinematics(freed, pose, &b);
  const int toe = skeleton.FindJoint("LeftToe");
  EXPECT_LT((a.world_positions[toe] - b.world_positions[toe]).norm(), 1e-12);
  EXPECT_FALSE(FreeLockedAxes(skeleton, {skeleton.FindJoint("LeftToe")}, &freed).ok());
}

}  // namespace
}  // namespace mocapsolve
