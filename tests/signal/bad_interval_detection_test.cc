#include "signal/bad_interval_detection.h"

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

TEST(DetectBad, FlagsJointsPastEitherThresholdAndTheirMarkers) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion reference = MakeDemoWalk(skeleton, 20, 30.0);
  Motion naive = reference;
  const int arm = skeleton.FindJoint("LeftForeArm");
  const int hand = skeleton.FindJoint("LeftHand");
  // Frames 5-9: the forearm bends 40 degrees more (the hand moves ~17 cm, turns 40 deg).
  for (int f = 5; f <= 9; ++f) {
    naive.frames[f].rotations[arm] = naive.frames[f].rotations[arm] * ExpMap(Eigen::Vector3d(0, DegToRad(40), 0));
  }
  std::vector<std::vector<char>> bad;
  ASSERT_TRUE(DetectBadJoints(skeleton, naive, reference, {10.0, DegToRad(30)}, &bad).ok());
  for (int f = 0; f < 20; ++f) {
    const bool inside = f >= 5 && f <= 9;
    EXPECT_EQ(bad[f][arm] != 0, inside) << f;   // Turned 40 deg (> 30), not moved.
    EXPECT_EQ(bad[f][hand] != 0, inside) << f;  // Moved and turned.
    EXPECT_FALSE(bad[f][skeleton.FindJoint("RightHand")]) << f;
  }
  // Rotation test off (pi): only joints that moved more than 10 cm remain.
  ASSERT_TRUE(DetectBadJoints(skeleton, naive, reference, {10.0, kPi}, &bad).ok());
  EXPECT_FALSE(bad[7][arm]);
  EXPECT_TRUE(bad[7][hand]);

  std::vector<MarkerSpec> specs = {{"LHND", {{hand, 1.0, {2, 0, 0}}}},
                                   {"BLEND", {{arm, 0.5, {0, 1, 0}}, {skeleton.FindJoint("Chest"), 0.5, {0, 1, 0}}}},
                                   {"RHND", {{skeleton.FindJoint("RightHand"), 1.0, {2, 0, 0}}}}};
  MarkerSet markers;
  ASSERT_TRUE(MarkerSet::Create(skeleton, specs, &markers).ok());
  ASSERT_TRUE(DetectBadJoints(skeleton, naive, reference, {10.0, DegToRad(30)}, &bad).ok());
  const auto marker_bad = BadMarkerSamples(markers, bad);
  EXPECT_TRUE(marker_bad[7][0]);
  EXPECT_TRUE(marker_bad[7][1]);   // Half its weight on the bad forearm.
  EXPECT_FALSE(marker_bad[7][2]);
  EXPECT_FALSE(marker_bad[2][0]);
}

TEST(DetectBad, FrameCountMismatchIsAnError) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::vector<std::vector<char>> bad;
  EXPECT_FALSE(DetectBadJoints(skeleton, MakeDemoWalk(skeleton, 5, 30), MakeDemoWalk(skeleton, 6, 30), {}, &bad).ok());
}

}  // namespace
}  // namespace mocapsolve
