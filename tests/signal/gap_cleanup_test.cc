#include "signal/gap_cleanup.h"

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

MarkerTrajectories Line(int frames) {
  MarkerTrajectories markers({"M"}, frames);
  for (int f = 0; f < frames; ++f) markers.SetSample(f, 0, Eigen::Vector3d(f, 2.0 * f, -f));
  return markers;
}

TEST(GapCleanup, RemovesOnlyEnclosedShortTracks) {
  MarkerTrajectories markers = Line(30);
  // valid 0-4 | gap 5-9 | track 10-11 | gap 12-19 | valid 20-29
  for (int f = 5; f <= 9; ++f) markers.SetMissing(f, 0);
  for (int f = 12; f <= 19; ++f) markers.SetMissing(f, 0);
  EXPECT_EQ(RemoveSmallTracks(2, &markers), 2);
  EXPECT_FALSE(markers.valid(10, 0));
  EXPECT_FALSE(markers.valid(11, 0));
  EXPECT_TRUE(markers.valid(4, 0));   // The leading run is not enclosed.
  EXPECT_TRUE(markers.valid(20, 0));  // Nor the trailing one.
  EXPECT_EQ(RemoveSmallTracks(5, &markers), 0);
}

TEST(GapCleanup, KeepsShortTracksThatHoldATrustedSample) {
  MarkerTrajectories markers = Line(30);
  // gap 5-9 | track 10-11 | gap 12-14 | track 15-17 | gap 18-19
  for (int f : {5, 6, 7, 8, 9, 12, 13, 14, 18, 19}) markers.SetMissing(f, 0);
  const auto trusted = [](int f, int m) { return m == 0 && f == 16; };
  EXPECT_EQ(RemoveSmallTracks(5, trusted, &markers), 2);
  EXPECT_FALSE(markers.valid(10, 0));
  for (int f = 15; f <= 17; ++f) EXPECT_TRUE(markers.valid(f, 0)) << f;
}

TEST(GapCleanup, FillsShortInteriorGapsExactlyOnALine) {
  MarkerTrajectories markers = Line(30);
  const MarkerTrajectories original = markers;
  for (int f = 10; f <= 12; ++f) markers.SetMissing(f, 0);  // 3 frames: filled.
  for (int f = 20; f <= 26; ++f) markers.SetMissing(f, 0);  // 7 frames: left.
  markers.SetMissing(0, 0);                                 // At the start: left.
  EXPECT_EQ(FillSmallGaps(5, &markers), 3);
  for (int f = 10; f <= 12; ++f) {
    ASSERT_TRUE(markers.valid(f, 0));
    // A straight path with one-sided difference tangents is reproduced exactly.
    EXPECT_LT((markers.position(f, 0) - original.position(f, 0)).norm(), 1e-12);
  }
  EXPECT_FALSE(markers.valid(20, 0));
  EXPECT_FALSE(markers.valid(0, 0));
}

}  // namespace
}  // namespace mocapsolve
