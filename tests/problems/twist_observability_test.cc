// TwistObservability: what the markers below a joint see of its twist once the joints below
// have turned to make up for it.
#include "problems/marker_solve/twist_observability.h"

#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

TEST(TwistObservability, WhatTheJointsBelowCannotMakeUp) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::mt19937 rng(3);
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, rng());
  const Pose pose = MakeDemoWalk(skeleton, 3, 30.0).frames[1];
  const int forearm = skeleton.FindJoint("LeftForeArm");
  const int hand = skeleton.FindJoint("LeftHand");
  ASSERT_GE(forearm, 0);
  ASSERT_GE(hand, 0);
  // No marker below the hand: nothing observes its twist.
  EXPECT_EQ(TwistObservability(skeleton, markers, pose, hand, Eigen::Vector3d::UnitX()), 0.0);
  // About the forearm's bone (the line to the hand's ball joint): the hand turns back, unseen.
  const Eigen::Vector3d bone = skeleton.offset(hand).normalized();
  EXPECT_LT(TwistObservability(skeleton, markers, pose, forearm, bone), 1e-9);
  // Normal to it the hand's origin moves 25 units per radian, which no turn of the hand undoes:
  // each of its three markers sees part of it.
  EXPECT_GT(TwistObservability(skeleton, markers, pose, forearm, bone.unitOrthogonal()), 10.0);
}

}  // namespace
}  // namespace mocapsolve
