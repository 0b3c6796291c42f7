#include "kinematics/marker_trajectories.h"

#include <cmath>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

MarkerTrajectories ThreeMarkers() {
  MarkerTrajectories t({"Sub:LBWT", "Sub:RBWT", "CLAV"}, 4);
  t.subject_prefixes = {"Sub:"};
  t.unit = Millimetres();
  t.frame_rate = 100.0;
  return t;
}

TEST(MarkerTrajectories, StartsAllMissing) {
  const MarkerTrajectories t = ThreeMarkers();
  EXPECT_EQ(t.num_frames(), 4);
  EXPECT_EQ(t.num_markers(), 3);
  EXPECT_EQ(t.positions().cols(), 12);
  EXPECT_EQ(t.CountMissing(), 12);
  for (int f = 0; f < 4; ++f) {
    for (int m = 0; m < 3; ++m) {
      EXPECT_FALSE(t.valid(f, m));
      EXPECT_TRUE(t.position(f, m).array().isNaN().all());
      EXPECT_EQ(t.residual(f, m), -1.0f);
    }
  }
}

// A copy sharing the samples keeps its own mask: marking a sample missing in one leaves the
// other's, and writing a position in either copies the array first.
TEST(MarkerTrajectories, SharingSamplesKeepsMasksApart) {
  MarkerTrajectories a = ThreeMarkers();
  a.SetSample(0, 0, Eigen::Vector3d(1, 2, 3));
  a.SetSample(1, 0, Eigen::Vector3d(4, 5, 6), 0.25f, 3);
  MarkerTrajectories b = a.SharingSamples();
  EXPECT_EQ(b.positions().data(), a.positions().data());  // One array.
  EXPECT_EQ(b.unit.name, "mm");
  EXPECT_EQ(b.residual(1, 0), 0.25f);
  EXPECT_EQ(b.camera_mask(1, 0), 3);
  b.SetMissing(0, 0);
  EXPECT_EQ(b.positions().data(), a.positions().data());  // Still one array.
  EXPECT_FALSE(b.valid(0, 0));
  EXPECT_TRUE(b.position(0, 0).array().isNaN().all());
  EXPECT_EQ(b.residual(0, 0), -1.0f);
  EXPECT_TRUE(a.valid(0, 0));
  EXPECT_EQ(a.position(0, 0), Eigen::Vector3d(1, 2, 3));
  b.SetSample(2, 2, Eigen::Vector3d(7, 8, 9));
  EXPECT_NE(b.positions().data(), a.positions().data());  // Copied on write.
  EXPECT_TRUE(b.positions().col(b.index(0, 0)).array().isNaN().all());  // NaN where b misses it.
  EXPECT_EQ(b.position(1, 0), Eigen::Vector3d(4, 5, 6));
  EXPECT_FALSE(a.valid(2, 2));
  EXPECT_TRUE(a.position(2, 2).array().isNaN().all());
  // Writing into the source copies it too; the other keeps the old sample.
  MarkerTrajectories c = a.SharingSamples();
  a.SetSample(1, 0, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(c.position(1, 0), Eigen::Vector3d(4, 5, 6));
  a.ScaleLengths(2.0);
  EXPECT_EQ(c.position(0, 0), Eigen::Vector3d(1, 2, 3));
  // An ordinary copy has its own array.
  const MarkerTrajectories d = c;
  EXPECT_NE(d.positions().data(), c.positions().data());
  EXPECT_EQ(d.position(1, 0), Eigen::Vector3d(4, 5, 6));
}

// Residuals and camera masks read as 0 (valid) and -1 (missing) until one is set.
TEST(MarkerTrajectories, ResidualsReadTheSameWhetherStoredOrNot) {
  MarkerTrajectories t = ThreeMarkers();
  t.SetSample(0, 1, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(t.residual(0, 1), 0.0f);
  EXPECT_EQ(t.residual(0, 0), -1.0f);
  EXPECT_EQ(t.camera_mask(0, 1), 0);
  t.SetSample(3, 2, Eigen::Vector3d(1, 2, 3), 1.5f);
  EXPECT_EQ(t.residual(3, 2), 1.5f);
  EXPECT_EQ(t.residual(0, 1), 0.0f);
  EXPECT_EQ(t.residual(0, 0), -1.0f);
  t.SetSample(0, 1, Eigen::Vector3d(1, 2, 3), -0.0f);  // Stored as it is.
  EXPECT_TRUE(std::signbit(t.residual(0, 1)));
  t.SetMissing(3, 2);
  EXPECT_EQ(t.residual(3, 2), -1.0f);
}

TEST(MarkerTrajectories, FrameMajorLayoutAndMaskFollowsSamples) {
  MarkerTrajectories t = ThreeMarkers();
  t.SetSample(2, 1, Eigen::Vector3d(1, 2, 3), 0.5f, 7);
  EXPECT_EQ(t.index(2, 1), 2 * 3 + 1);
  EXPECT_EQ(t.positions().col(7), Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE(t.valid(2, 1));
  EXPECT_EQ(t.valid_mask()[7], 1);
  EXPECT_EQ(t.residual(2, 1), 0.5f);
  EXPECT_EQ(t.camera_mask(2, 1), 7);
  EXPECT_EQ(t.CountMissing(), 11);
  EXPECT_EQ(t.CountMissing(1), 3);

  // Zero is a position like any other here; only the readers map file gap conventions.
  t.SetSample(0, 0, Eigen::Vector3d::Zero());
  EXPECT_TRUE(t.valid(0, 0));
  EXPECT_EQ(t.residual(0, 0), 0.0f);

  // A non-finite position is stored as missing, keeping NaN and mask in step.
  t.SetSample(3, 2, Eigen::Vector3d(1, NAN, 3), 2.0f);
  EXPECT_FALSE(t.valid(3, 2));
  EXPECT_TRUE(t.position(3, 2).array().isNaN().all());
  EXPECT_EQ(t.residual(3, 2), -1.0f);

  t.SetMissing(2, 1);
  EXPECT_FALSE(t.valid(2, 1));
  EXPECT_TRUE(t.position(2, 1).array().isNaN().all());
  EXPECT_EQ(t.camera_mask(2, 1), 0);
}

TEST(MarkerTrajectories, NegativeResidualOfValidSampleMeansUnknown) {
  MarkerTrajectories t = ThreeMarkers();
  t.SetSample(1, 1, Eigen::Vector3d(1, 1, 1), -1.0f);
  EXPECT_TRUE(t.valid(1, 1));
  EXPECT_EQ(t.residual(1, 1), 0.0f);
}

TEST(MarkerTrajectories, FindMarkerWithAndWithoutSubjectPrefix) {
  MarkerTrajectories t = ThreeMarkers();
  EXPECT_EQ(t.FindMarker("Sub:LBWT"), 0);
  EXPECT_EQ(t.FindMarker("LBWT"), 0);
  EXPECT_EQ(t.FindMarker("RBWT"), 1);
  EXPECT_EQ(t.FindMarker("CLAV"), 2);
  EXPECT_EQ(t.FindMarker("STRN"), -1);
  EXPECT_EQ(t.FindMarker("lbwt"), -1);  // Labels are case sensitive.

  // Two subjects with the same marker name: only the prefixed label is unambiguous.
  MarkerTrajectories two({"A:LBWT", "B:LBWT"}, 1);
  two.subject_prefixes = {"A:", "B:"};
  EXPECT_EQ(two.FindMarker("LBWT"), -1);
  EXPECT_EQ(two.FindMarker("B:LBWT"), 1);
}

// Every n-th frame (a fit's frames spread over a take): samples as they were, missing ones
// missing, the frame rate divided so times stay right.
TEST(EveryNthFrame, KeepsFramesZeroNTwoNAndTheirTimes) {
  MarkerTrajectories t({"A", "B"}, 7);
  t.unit = Millimetres();
  t.frame_rate = 120.0;
  t.first_frame = 50;
  for (int f = 0; f < 7; ++f) t.SetSample(f, 0, Eigen::Vector3d(f, 0, 0), 0.5f, 2);
  t.SetSample(3, 1, Eigen::Vector3d(1, 2, 3));
  const MarkerTrajectories every3 = EveryNthFrame(t, 3);
  ASSERT_EQ(every3.num_frames(), 3);  // Frames 0, 3, 6.
  EXPECT_EQ(every3.num_markers(), 2);
  EXPECT_EQ(every3.frame_rate, 40.0);
  EXPECT_EQ(every3.first_frame, 50);
  EXPECT_EQ(every3.unit.name, "mm");
  for (int f = 0; f < 3; ++f) {
    EXPECT_EQ(every3.position(f, 0), Eigen::Vector3d(3 * f, 0, 0));
    EXPECT_EQ(every3.residual(f, 0), 0.5f);
    EXPECT_EQ(every3.camera_mask(f, 0), 2);
  }
  EXPECT_FALSE(every3.valid(0, 1));
  EXPECT_EQ(every3.position(1, 1), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(EveryNthFrame(t, 4).num_frames(), 2);  // 0, 4.
  EXPECT_EQ(EveryNthFrame(t, 1).num_frames(), 7);
  EXPECT_EQ(EveryNthFrame(t, 1).frame_rate, 120.0);
}

TEST(SplitSubjectPrefix, KnownPrefixesThenColon) {
  SubjectLabel s = SplitSubjectPrefix("TakeoMonday:LBWT", {"TakeoMonday:"});
  EXPECT_EQ(s.prefix, "TakeoMonday:");
  EXPECT_EQ(s.name, "LBWT");
  // Longest known prefix wins.
  s = SplitSubjectPrefix("Sub:Two:LBWT", {"Sub:", "Sub:Two:"});
  EXPECT_EQ(s.prefix, "Sub:Two:");
  EXPECT_EQ(s.name, "LBWT");
  // No known prefixes: Vicon's Subject:Marker convention.
  s = SplitSubjectPrefix("Nick01:ARIEL");
  EXPECT_EQ(s.prefix, "Nick01:");
  EXPECT_EQ(s.name, "ARIEL");
  // Dots are not separators (OpenSim names).
  s = SplitSubjectPrefix("R.ASIS");
  EXPECT_EQ(s.prefix, "");
  EXPECT_EQ(s.name, "R.ASIS");
  // Empty known prefixes (JA1Gait35 stores one) are ignored; a trailing colon is no split.
  s = SplitSubjectPrefix("C7", {""});
  EXPECT_EQ(s.name, "C7");
  s = SplitSubjectPrefix("odd:");
  EXPECT_EQ(s.prefix, "");
  EXPECT_EQ(s.name, "odd:");
}

TEST(ConvertUnits, ScalesValidSamplesAndResidualsOnly) {
  MarkerTrajectories t = ThreeMarkers();
  t.SetSample(0, 0, Eigen::Vector3d(1000, -2000, 500), 2.0f);
  ASSERT_TRUE(ConvertUnits(Metres(), &t).ok());
  EXPECT_EQ(t.unit.name, "m");
  EXPECT_TRUE(t.position(0, 0).isApprox(Eigen::Vector3d(1, -2, 0.5)));
  EXPECT_FLOAT_EQ(t.residual(0, 0), 0.002f);
  EXPECT_FALSE(t.valid(0, 1));
  EXPECT_TRUE(t.position(0, 1).array().isNaN().all());
  EXPECT_EQ(t.residual(0, 1), -1.0f);  // The missing marker stays -1, not -0.001.
  ASSERT_TRUE(ConvertUnits(Centimetres(), &t).ok());
  EXPECT_TRUE(t.position(0, 0).isApprox(Eigen::Vector3d(100, -200, 50)));
}

TEST(ConvertUnits, UnknownUnitIsAnErrorAndChangesNothing) {
  MarkerTrajectories t = ThreeMarkers();
  t.unit = LengthUnit();
  t.SetSample(0, 0, Eigen::Vector3d(1, 2, 3));
  const Status status = ConvertUnits(Metres(), &t);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("unknown"), std::string::npos) << status.message();
  EXPECT_EQ(t.position(0, 0), Eigen::Vector3d(1, 2, 3));
  t.unit = Millimetres();
  EXPECT_FALSE(ConvertUnits(LengthUnit(), &t).ok());
}

TEST(LengthUnitFromName, CommonSpellings) {
  EXPECT_EQ(LengthUnitFromName("mm").metres_per_unit, 0.001);
  EXPECT_EQ(LengthUnitFromName("MM ").metres_per_unit, 0.001);
  EXPECT_EQ(LengthUnitFromName("meters").metres_per_unit, 1.0);
  EXPECT_EQ(LengthUnitFromName("cm").metres_per_unit, 0.01);
  EXPECT_EQ(LengthUnitFromName("in").metres_per_unit, 0.0254);
  EXPECT_FALSE(LengthUnitFromName("furlong").known());
  EXPECT_FALSE(LengthUnitFromName("").known());
}

}  // namespace
}  // namespace mocapsolve
