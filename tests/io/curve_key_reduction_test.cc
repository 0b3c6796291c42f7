#include "io/curve_key_reduction.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// The keys' linear interpolation at every frame, evaluated here independently of the reducer.
std::vector<double> Interpolate(const CurveKeys& keys, int n) {
  std::vector<double> out(n);
  for (size_t k = 0; k + 1 < keys.frames.size(); ++k) {
    const int a = keys.frames[k], b = keys.frames[k + 1];
    for (int i = a; i <= b; ++i) {
      out[i] = keys.values[k] + (static_cast<double>(keys.values[k + 1]) - keys.values[k]) * (i - a) / (b - a);
    }
  }
  if (keys.frames.size() == 1) out[0] = keys.values[0];
  return out;
}

// A joint angle as a retarget writes it: smooth motion in degrees plus solver noise.
std::vector<float> NoisyCurve(int n, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::vector<float> v(n);
  for (int i = 0; i < n; ++i) {
    v[i] = static_cast<float>(40.0 * std::sin(0.03 * i) + 12.0 * std::sin(0.11 * i + 1.0) + noise(random));
  }
  return v;
}

TEST(CurveKeyReduction, EverySampleStaysWithinTheTolerance) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const std::vector<float> samples = NoisyCurve(1000, seed);
    size_t previous_keys = samples.size() + 1;
    for (double tolerance : {1e-4, 1e-3, 1e-2, 1e-1, 1.0}) {
      const CurveKeys keys = ReduceLinearKeys(samples, tolerance);
      ASSERT_EQ(keys.frames.size(), keys.values.size());
      ASSERT_EQ(keys.frames.front(), 0);
      ASSERT_EQ(keys.frames.back(), 999);
      for (size_t k = 1; k < keys.frames.size(); ++k) ASSERT_LT(keys.frames[k - 1], keys.frames[k]);
      const std::vector<double> line = Interpolate(keys, 1000);
      double worst = 0.0;
      for (int i = 0; i < 1000; ++i) worst = std::max(worst, std::abs(line[i] - samples[i]));
      // The bound, plus the float rounding of a kept value (values ~50: 4e-6).
      EXPECT_LE(worst, tolerance + 1e-5) << "seed " << seed << ", tolerance " << tolerance;
      EXPECT_LT(keys.frames.size(), previous_keys) << "a looser tolerance keeps fewer keys";
      previous_keys = keys.frames.size();
    }
  }
}

TEST(CurveKeyReduction, ZeroToleranceIsExact) {
  const std::vector<float> samples = NoisyCurve(300, 7);
  const CurveKeys keys = ReduceLinearKeys(samples, 0.0);
  ASSERT_EQ(keys.frames.size(), samples.size());  // A curved, noisy curve: no sample is on a line.
  for (size_t i = 0; i < samples.size(); ++i) EXPECT_EQ(keys.values[i], samples[i]);  // Bit for bit.
  const CurveKeys still = ReduceLinearKeys(std::vector<float>(500, 12.5f), 0.0);
  EXPECT_EQ(still.frames, (std::vector<int>{0, 499}));
  EXPECT_EQ(still.values, (std::vector<float>{12.5f, 12.5f}));
}

TEST(CurveKeyReduction, ALineNeedsTwoKeysAndAKinkThree) {
  std::vector<float> ramp(200), kink(200);
  for (int i = 0; i < 200; ++i) {
    ramp[i] = static_cast<float>(0.25 * i);
    kink[i] = static_cast<float>(i < 120 ? 0.5 * i : 60.0 - 0.25 * (i - 120));
  }
  EXPECT_EQ(ReduceLinearKeys(ramp, 1e-4).frames.size(), 2u);
  const CurveKeys keys = ReduceLinearKeys(kink, 1e-4);
  ASSERT_EQ(keys.frames.size(), 3u);
  EXPECT_EQ(keys.frames[1], 120);
}

TEST(CurveKeyReduction, ShortCurves) {
  EXPECT_TRUE(ReduceLinearKeys({}, 0.1).frames.empty());
  EXPECT_EQ(ReduceLinearKeys({3.0f}, 0.1).frames, std::vector<int>{0});
  EXPECT_EQ(ReduceLinearKeys({3.0f, 4.0f}, 0.1).frames, (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace mocapsolve
