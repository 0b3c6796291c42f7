// Algorithm 3's Hermite refill: exact when the offset between original and reference is
// linear, C1-continuous at the gap edges, every degenerate case, the velocity clamp, and
// edge velocities fitted over several samples so a jittery marker's fill stays near it.
#include "signal/gap_fill.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// One marker moving on a curve; the reference is the curve plus an offset that varies
// as `offset(t)`.
template <typename Offset>
void MakePaths(int frames, Offset offset, MarkerTrajectories* original, MarkerTrajectories* reference) {
  *original = MarkerTrajectories({"M"}, frames);
  *reference = MarkerTrajectories({"M"}, frames);
  for (int f = 0; f < frames; ++f) {
    const double t = f;
    const Eigen::Vector3d x(std::sin(0.1 * t), 0.02 * t * t, std::cos(0.07 * t));
    original->SetSample(f, 0, x);
    reference->SetSample(f, 0, x - offset(t));
  }
}

TEST(GapFill, FindsMaximalRuns) {
  MarkerTrajectories markers({"A", "B"}, 10);
  for (int f = 0; f < 10; ++f) {
    markers.SetSample(f, 0, Eigen::Vector3d(f, 0, 0));
    if (f >= 3 && f <= 5) continue;
    markers.SetSample(f, 1, Eigen::Vector3d(0, f, 0));
  }
  markers.SetMissing(0, 0);
  markers.SetMissing(9, 0);
  const std::vector<Gap> gaps = FindGaps(markers);
  ASSERT_EQ(gaps.size(), 3u);
  EXPECT_EQ(gaps[0].marker, 0); EXPECT_EQ(gaps[0].first, 0); EXPECT_EQ(gaps[0].last, 0);
  EXPECT_EQ(gaps[1].marker, 0); EXPECT_EQ(gaps[1].first, 9); EXPECT_EQ(gaps[1].last, 9);
  EXPECT_EQ(gaps[2].marker, 1); EXPECT_EQ(gaps[2].first, 3); EXPECT_EQ(gaps[2].length(), 3);
}

TEST(GapFill, ConstantOrLinearOffsetIsRecoveredExactly) {
  // A Hermite whose end tangents are the one-sided differences of a linear offset is that
  // line, so the fill reproduces the original exactly.
  MarkerTrajectories original, reference;
  MakePaths(60, [](double t) { return Eigen::Vector3d(0.5 + 0.01 * t, -0.2, 0.003 * t); }, &original, &reference);
  MarkerTrajectories damaged = original;
  for (int f = 20; f <= 35; ++f) damaged.SetMissing(f, 0);
  ASSERT_TRUE(FillGapFromReference(FindGaps(damaged)[0], reference, GapFillOptions(), &damaged).ok());
  for (int f = 0; f < 60; ++f) EXPECT_LT((damaged.position(f, 0) - original.position(f, 0)).norm(), 1e-12) << f;
}

TEST(GapFill, C1ContinuousAtTheEdges) {
  // A curved offset: the fill is not exact inside, but position and velocity of the
  // offset meet the known ones at both edges (to the one-sided differences used).
  MarkerTrajectories original, reference;
  MakePaths(80, [](double t) { return Eigen::Vector3d(std::sin(0.05 * t), 0.001 * t * t, 0.0); }, &original, &reference);
  MarkerTrajectories filled = original;
  const int s = 30, e = 49;
  for (int f = s; f <= e; ++f) filled.SetMissing(f, 0);
  ASSERT_TRUE(FillGapFromReference(FindGaps(filled)[0], reference, GapFillOptions(), &filled).ok());
  auto offset = [&](const MarkerTrajectories& x, int f) { return Eigen::Vector3d(x.position(f, 0) - reference.position(f, 0)); };
  // Velocity of the filled offset entering the gap equals the one before it (C1): the
  // Hermite's slope at the edge is the given tangent, so the second difference across the
  // edge is small compared to the offset's own variation.
  const Eigen::Vector3d jump_in = (offset(filled, s) - offset(filled, s - 1)) - (offset(filled, s - 1) - offset(filled, s - 2));
  const Eigen::Vector3d jump_out = (offset(filled, e + 2) - offset(filled, e + 1)) - (offset(filled, e + 1) - offset(filled, e));
  EXPECT_LT(jump_in.norm(), 5e-3);
  EXPECT_LT(jump_out.norm(), 5e-3);
  // Without the velocity terms (a clamp of 0) the velocity jumps by the offset's slope.
  MarkerTrajectories c0 = original;
  for (int f = s; f <= e; ++f) c0.SetMissing(f, 0);
  GapFillOptions zero;
  zero.velocity_clamp = 0.0;
  ASSERT_TRUE(FillGapFromReference(FindGaps(c0)[0], reference, zero, &c0).ok());
  const Eigen::Vector3d jump_c0 = (offset(c0, s) - offset(c0, s - 1)) - (offset(c0, s - 1) - offset(c0, s - 2));
  EXPECT_GT(jump_c0.norm(), 5.0 * jump_in.norm());
}

TEST(GapFill, LinearOffsetStaysExactWithMoreEdgeSamples) {
  // A line fitted to a linear offset is that line: more edge samples change nothing there.
  MarkerTrajectories original, reference;
  MakePaths(60, [](double t) { return Eigen::Vector3d(0.5 + 0.01 * t, -0.2, 0.003 * t); }, &original, &reference);
  MarkerTrajectories damaged = original;
  for (int f = 20; f <= 35; ++f) damaged.SetMissing(f, 0);
  GapFillOptions options;
  options.edge_samples = 10;
  ASSERT_TRUE(FillGapFromReference(FindGaps(damaged)[0], reference, options, &damaged).ok());
  for (int f = 0; f < 60; ++f) EXPECT_LT((damaged.position(f, 0) - original.position(f, 0)).norm(), 1e-12) << f;
}

TEST(GapFill, JitteryEdgesAreAveragedOverEdgeSamples) {
  // A constant true offset seen through +-1 jitter alternating frame by frame (a noisy
  // marker): the one-sided difference reads a slope of 2 per frame at each edge, which the
  // Hermite tangent scales by the gap's length; a line over 10 samples reads almost none.
  MarkerTrajectories original, reference;
  MakePaths(80, [](double) { return Eigen::Vector3d(0.3, 0.0, 0.0); }, &original, &reference);
  MarkerTrajectories noisy = original;
  for (int f = 0; f < 80; ++f) {
    noisy.SetSample(f, 0, original.position(f, 0) + Eigen::Vector3d(f % 2 == 0 ? 1.0 : -1.0, 0.0, 0.0));
  }
  const int s = 30, e = 49;
  auto worst_error = [&](int edge_samples) {
    MarkerTrajectories filled = noisy;
    for (int f = s; f <= e; ++f) filled.SetMissing(f, 0);
    GapFillOptions options;
    options.edge_samples = edge_samples;
    EXPECT_TRUE(FillGapFromReference(FindGaps(filled)[0], reference, options, &filled).ok());
    double worst = 0.0;
    for (int f = s; f <= e; ++f) worst = std::max(worst, (filled.position(f, 0) - original.position(f, 0)).norm());
    return worst;
  };
  const double thesis = worst_error(2), fitted = worst_error(10);
  EXPECT_GT(thesis, 3.0);   // Tangents of 2 per frame over a 21-frame span: 4.8 off.
  EXPECT_LT(fitted, 1.5);   // The edge samples' own jitter (1), no more.
}

TEST(GapFill, DegenerateGaps) {
  MarkerTrajectories original, reference;
  MakePaths(30, [](double) { return Eigen::Vector3d(1.0, 2.0, 3.0); }, &original, &reference);
  // At the start, at the end, one frame, the whole take.
  for (auto [first, last] : std::vector<std::pair<int, int>>{{0, 4}, {25, 29}, {10, 10}, {0, 29}}) {
    MarkerTrajectories damaged = original;
    for (int f = first; f <= last; ++f) damaged.SetMissing(f, 0);
    const std::vector<Gap> gaps = FindGaps(damaged);
    ASSERT_EQ(gaps.size(), 1u);
    ASSERT_TRUE(FillGapFromReference(gaps[0], reference, GapFillOptions(), &damaged).ok());
    for (int f = first; f <= last; ++f) {
      ASSERT_TRUE(damaged.valid(f, 0));
      // Constant offset: every case but the whole take restores the original; a marker
      // missing all take gets the reference itself.
      const Eigen::Vector3d expected = (first == 0 && last == 29) ? reference.position(f, 0) : original.position(f, 0);
      EXPECT_LT((damaged.position(f, 0) - expected).norm(), 1e-12) << first << ":" << last << " @" << f;
    }
  }
}

TEST(GapFill, ErrorsOnMismatchOrMissingReference) {
  MarkerTrajectories original, reference;
  MakePaths(20, [](double) { return Eigen::Vector3d::Zero(); }, &original, &reference);
  MarkerTrajectories damaged = original;
  damaged.SetMissing(5, 0);
  const Gap gap = FindGaps(damaged)[0];
  MarkerTrajectories short_reference({"M"}, 10);
  EXPECT_FALSE(FillGapFromReference(gap, short_reference, GapFillOptions(), &damaged).ok());
  reference.SetMissing(5, 0);
  const Status status = FillGapFromReference(gap, reference, GapFillOptions(), &damaged);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("frame 5"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace mocapsolve
