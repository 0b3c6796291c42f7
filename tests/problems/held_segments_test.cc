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
