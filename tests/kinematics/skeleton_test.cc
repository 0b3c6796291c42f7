#include "kinematics/skeleton.h"

#include <gtest/gtest.h>

#include "tests/kinematics/test_rigs.h"

namespace mocapsolve {
namespace {

TEST(Skeleton, SubtreeRangesInPreorder) {
  const Skeleton s = testing::MakeTestSkeleton();
  ASSERT_EQ(s.num_joints(), 11);
  EXPECT_EQ(s.subtree_end(0), 11);
  EXPECT_EQ(s.subtree_end(1), 9);   // spine: chest, neck, head, arms.
  EXPECT_EQ(s.subtree_end(2), 9);
  EXPECT_EQ(s.subtree_end(3), 5);   // neck: head.
  EXPECT_EQ(s.subtree_end(4), 5);
  EXPECT_EQ(s.subtree_end(5), 7);
  EXPECT_EQ(s.subtree_end(9), 11);
  EXPECT_TRUE(s.IsAncestorOrSelf(2, 6));
  EXPECT_FALSE(s.IsAncestorOrSelf(5, 8));
  EXPECT_FALSE(s.IsAncestorOrSelf(9, 4));
  EXPECT_EQ(s.FindJoint("l_hand"), 6);
  EXPECT_EQ(s.FindJoint("nope"), -1);
  EXPECT_TRUE(s.has_translation_channels(9));
  EXPECT_FALSE(s.has_translation_channels(1));
  EXPECT_TRUE(s.has_rest_rotation(2));
  EXPECT_FALSE(s.has_rest_rotation(1));
}

TEST(Skeleton, RejectsBadSpecs) {
  Skeleton s;
  JointSpec root{"root", -1, Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(), {}, std::nullopt, {}};
  JointSpec child{"child", 0, Eigen::Vector3d(0, 1, 0), Eigen::Quaterniond::Identity(), {}, std::nullopt, {}};
  EXPECT_FALSE(Skeleton::Create({}, {}, Metres(), &s).ok());
  EXPECT_TRUE(Skeleton::Create({root, child}, {}, Metres(), &s).ok());

  JointSpec forward = child;
  forward.parent = 1;  // Parent must come first.
  EXPECT_FALSE(Skeleton::Create({root, forward}, {}, Metres(), &s).ok());
  JointSpec duplicate = child;
  duplicate.name = "root";
  const Status status = Skeleton::Create({root, duplicate}, {}, Metres(), &s);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("duplicate"), std::string::npos);
  JointSpec nan = child;
  nan.offset.x() = std::nan("");
  EXPECT_FALSE(Skeleton::Create({root, nan}, {}, Metres(), &s).ok());
  JointSpec scaled = child;
  scaled.rest_rotation = Eigen::Quaterniond(2, 0, 0, 0);
  EXPECT_FALSE(Skeleton::Create({root, scaled}, {}, Metres(), &s).ok());
  JointSpec channels = child;
  channels.channels = {Channel::kXrotation, Channel::kXrotation};
  EXPECT_FALSE(Skeleton::Create({root, channels}, {}, Metres(), &s).ok());
  EXPECT_FALSE(Skeleton::Create({root, child}, {{"end", 5, {0, 0, 0}}}, Metres(), &s).ok());
}

}  // namespace
}  // namespace mocapsolve
