// Segments no marker observes (problems/marker_solve/held_segments.h) on the demo character
// with 3 markers around each bone (synthetic_marker_set.h), cut to a sparse protocol's.
#include "problems/marker_solve/held_segments.h"

#include <set>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

// The synthetic set's markers on joints not in `without`.
MarkerSet Without(const Skeleton& skeleton, const MarkerSet& all, const std::set<std::string>& without) {
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < all.num_markers(); ++m) {
    if (!without.count(skeleton.name(all.marker(m).attachments[0].joint))) specs.push_back(all.marker(m));
  }
  MarkerSet kept;
  EXPECT_TRUE(MarkerSet::Create(skeleton, specs, &kept).ok());
  return kept;
}

const std::set<std::string> kUpperBody = {"Spine", "Chest", "Neck", "Head", "LeftShoulder", "LeftArm", "LeftForeArm",
                                          "LeftHand", "RightShoulder", "RightArm", "RightForeArm", "RightHand"};

TEST(HeldSegments, ALowerBodySetHoldsTheSpineAndAllAboveIt) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const MarkerSet all = MakeSyntheticMarkerSet(skeleton, 3, 7);
  EXPECT_TRUE(FindHeldSegments(skeleton, all).tops.empty());
  EXPECT_TRUE(AttachableJoints(skeleton, all).empty());  // Nothing excluded: every joint allowed.
  const MarkerSet legs = Without(skeleton, all, kUpperBody);
  const HeldSegments held = FindHeldSegments(skeleton, legs);
  EXPECT_EQ(held.tops, std::vector<std::string>{"Spine"});
  EXPECT_EQ(held.joints, static_cast<int>(kUpperBody.size()));
  // The held subtree (12 joints) is no attach candidate; every other joint is.
  const std::vector<int> attachable = AttachableJoints(skeleton, legs);
  EXPECT_EQ(attachable.size(), static_cast<size_t>(skeleton.num_joints()) - kUpperBody.size());
  for (int j : attachable) EXPECT_FALSE(kUpperBody.count(skeleton.name(j))) << skeleton.name(j);
  EXPECT_TRUE(MissingSegments(skeleton, legs, all).empty());
}

TEST(HeldSegments, AHeldLeafStaysAttachable) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const MarkerSet all = MakeSyntheticMarkerSet(skeleton, 3, 7);
  const MarkerSet no_toes = Without(skeleton, all, {"LeftToe"});
  EXPECT_EQ(FindHeldSegments(skeleton, no_toes).tops, std::vector<std::string>{"LeftToe"});
  EXPECT_TRUE(AttachableJoints(skeleton, no_toes).empty());
}

// A held end segment (a foot with its toe, a hand with its fingers) stays attachable: an
// association that left a foot's markers on the shin needs the attach rounds to move them
// onto the foot. A held arm (upper arm, forearm, hand) does not: one marker there would
// swing the whole arm.
TEST(HeldSegments, AHeldEndSegmentStaysAttachableAHeldLimbDoesNot) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const MarkerSet all = MakeSyntheticMarkerSet(skeleton, 3, 7);
  const MarkerSet no_foot = Without(skeleton, all, {"LeftFoot", "LeftToe"});
  EXPECT_EQ(FindHeldSegments(skeleton, no_foot).tops, std::vector<std::string>{"LeftFoot"});
  EXPECT_TRUE(AttachableJoints(skeleton, no_foot).empty());
  const std::set<std::string> arm = {"LeftArm", "LeftForeArm", "LeftHand"};
  const std::vector<int> attachable = AttachableJoints(skeleton, Without(skeleton, all, arm));
  EXPECT_EQ(attachable.size(), static_cast<size_t>(skeleton.num_joints()) - arm.size());
  for (int j : attachable) EXPECT_FALSE(arm.count(skeleton.name(j))) << skeleton.name(j);
}

// The pelvis needs a marker on its own joint or a child of it that leads to no leg (the
// demo's Spine, as CMU's lowerback carries LFWT): both left out here.
TEST(HeldSegments, MissingFeetAndPelvisAreNamedWithTheTemplatesMarkers) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const MarkerSet all = MakeSyntheticMarkerSet(skeleton, 3, 7);
  const std::vector<std::string> missing =
      MissingSegments(skeleton, Without(skeleton, all, {"Hips", "Spine", "RightFoot", "RightToe"}), all);
  ASSERT_EQ(missing.size(), 2u);
  EXPECT_THAT(missing[0], HasSubstr("pelvis (Hips; the template puts "));
  EXPECT_THAT(missing[1], HasSubstr("right_foot (RightFoot; the template puts "));
}

}  // namespace
}  // namespace mocapsolve
