// Cutting a rough run whole (signal/rough_run_extension.h): a noise run detected only in
// its middle is extended to exactly its noisy samples (the clean neighbours that see one
// noisy sample stay); a calm marker beside the gap is not touched; the walk stops at a
// missing sample and at max_extent; the residual's second difference ignores the
// reference's own motion.
#include "signal/rough_run_extension.h"

#include <cmath>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// A marker on an accelerating curve (reference), the samples = reference + a constant
// offset, plus `noise(f)` on frames [first, last].
void MakePaths(int frames, int first, int last, MarkerTrajectories* samples, MarkerTrajectories* reference) {
  *samples = MarkerTrajectories({"M"}, frames);
  *reference = MarkerTrajectories({"M"}, frames);
  for (int f = 0; f < frames; ++f) {
    const Eigen::Vector3d r(std::sin(0.3 * f), 0.05 * f * f, std::cos(0.2 * f));
    reference->SetSample(f, 0, r);
    Eigen::Vector3d x = r + Eigen::Vector3d(0.01, -0.02, 0.03);
    // Alternating +-1 per axis, with a small draw (0.2) at the run's second sample and
    // at its end: deterministic "white" noise.
    if (f >= first && f <= last) {
      const double size = (f == first + 1 || f == last) ? 0.2 : 1.0;
      x += size * (f % 2 == 0 ? 1.0 : -1.0) * Eigen::Vector3d(1.0, 1.0, 1.0);
    }
    samples->SetSample(f, 0, x);
  }
}

TEST(RoughRunExtensionTest, TheResidualsSecondDifferenceIgnoresTheReferencesMotion) {
  MarkerTrajectories samples, reference;
  MakePaths(50, 100, 99, &samples, &reference);  // No noise.
  for (int f = 1; f < 49; ++f) EXPECT_NEAR(SecondDifference(samples, &reference, 0, f), 0.0, 1e-12);
  EXPECT_EQ(SecondDifference(samples, &reference, 0, 0), -1.0);
  EXPECT_EQ(SecondDifference(samples, &reference, 0, 49), -1.0);
  EXPECT_NEAR(MedianSecondDifference(samples, &reference, 0, 0, 49), 0.0, 1e-12);
  // Without a reference: the samples' own second difference, the reference's acceleration
  // (y'' = 0.1 a frame squared) with the sine and cosine's, over the frames asked for only.
  auto own = [&](int f) {
    return (reference.position(f + 1, 0) - 2.0 * reference.position(f, 0) + reference.position(f - 1, 0)).norm();
  };
  EXPECT_NEAR(SecondDifference(samples, nullptr, 0, 7), own(7), 1e-12);
  EXPECT_GT(own(7), 0.1);
  EXPECT_NEAR(MedianSecondDifference(samples, nullptr, 0, 7, 7), own(7), 1e-12);
  EXPECT_EQ(MedianSecondDifference(samples, nullptr, 0, 49, 60), -1.0);  // No frame in range has one.
}

TEST(RoughRunExtensionTest, ANoiseRunDetectedInItsMiddleIsCutToExactlyItsNoisySamples) {
  MarkerTrajectories samples, reference;
  MakePaths(60, 20, 35, &samples, &reference);
  MarkerTrajectories x = samples, also = samples;
  for (int f = 25; f <= 30; ++f) x.SetMissing(f, 0);
  const int cut = ExtendRoughRun({0, 25, 30}, samples, reference, 0.05, 30, &x, &also);
  EXPECT_EQ(cut, 10);  // 20-24 and 31-35.
  for (int f = 0; f < 60; ++f) {
    const bool noisy = f >= 20 && f <= 35;
    EXPECT_EQ(x.valid(f, 0), !noisy) << "frame " << f;
    if (f < 25 || f > 30) {
      EXPECT_EQ(also.valid(f, 0), !noisy) << "frame " << f;
    }
  }
}

TEST(RoughRunExtensionTest, ACalmNeighbourhoodIsNotTouched) {
  MarkerTrajectories samples, reference;
  MakePaths(60, 25, 30, &samples, &reference);
  MarkerTrajectories x = samples;
  for (int f = 25; f <= 30; ++f) x.SetMissing(f, 0);
  // The run is detected whole: only its clean neighbours are rough, and they stay.
  EXPECT_EQ(ExtendRoughRun({0, 25, 30}, samples, reference, 0.05, 30, &x), 0);
  for (int f = 0; f < 60; ++f) EXPECT_EQ(x.valid(f, 0), f < 25 || f > 30) << "frame " << f;
  // A threshold above the noise cuts nothing either.
  MarkerTrajectories y = samples;
  for (int f = 27; f <= 28; ++f) y.SetMissing(f, 0);
  EXPECT_EQ(ExtendRoughRun({0, 27, 28}, samples, reference, 100.0, 30, &y), 0);
}

TEST(RoughRunExtensionTest, TheWalkStopsAtAMissingSampleAndAtMaxExtent) {
  MarkerTrajectories samples, reference;
  MakePaths(60, 10, 45, &samples, &reference);
  samples.SetMissing(22, 0);  // Missing before detection: the left walk ends at 23.
  MarkerTrajectories x = samples;
  for (int f = 27; f <= 28; ++f) x.SetMissing(f, 0);
  // Left: stretch from 24 (s(23) undefined), interior 25-26. Right: at most 3 cut, 29-31.
  EXPECT_EQ(ExtendRoughRun({0, 27, 28}, samples, reference, 0.05, 3, &x), 5);
  for (int f = 23; f <= 32; ++f) {
    EXPECT_EQ(x.valid(f, 0), f == 23 || f == 24 || f == 32) << "frame " << f;
  }
}

}  // namespace
}  // namespace mocapsolve
