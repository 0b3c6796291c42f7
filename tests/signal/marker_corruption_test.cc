#include "signal/marker_corruption.h"

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// 6 markers on a line 10 units apart, moving together.
MarkerTrajectories Clean(int frames) {
  MarkerTrajectories markers({"A", "B", "C", "D", "E", "F"}, frames);
  for (int f = 0; f < frames; ++f) {
    for (int m = 0; m < 6; ++m) markers.SetSample(f, m, Eigen::Vector3d(10.0 * m, 0.1 * f, 0));
  }
  return markers;
}

TEST(MarkerCorruption, MaskMatchesTheDamageAndIsReproducible) {
  CorruptionOptions options;
  options.seed = 7;
  options.cluster_radius = 15.0;
  options.fly_off_distance = 30.0;
  options.swap_radius = 12.0;
  options.noise_sigma = 2.0;
  const MarkerTrajectories clean = Clean(300);
  MarkerTrajectories a = clean, b = clean;
  CorruptionMask mask_a, mask_b;
  CorruptMarkers(options, &a, &mask_a);
  CorruptMarkers(options, &b, &mask_b);
  EXPECT_EQ(mask_a, mask_b);
  int counts[256] = {0};
  for (int f = 0; f < 300; ++f) {
    for (int m = 0; m < 6; ++m) {
      const char kind = mask_a[f][m];
      ++counts[static_cast<unsigned char>(kind)];
      if (kind == 0) {
        ASSERT_TRUE(a.valid(f, m));
        EXPECT_EQ(a.position(f, m), clean.position(f, m));  // Clean samples untouched.
      } else if (kind == 'g') {
        EXPECT_FALSE(a.valid(f, m));
      } else {
        ASSERT_TRUE(a.valid(f, m));
        EXPECT_GT((a.position(f, m) - clean.position(f, m)).norm(), 0.0) << kind;
      }
      if (kind == 's') {
        // Swapped with a neighbour 10 units away.
        EXPECT_NEAR((a.position(f, m) - clean.position(f, m)).norm(), 10.0, 1e-12);
      }
    }
  }
  EXPECT_GT(counts['g'], 0);
  EXPECT_GT(counts['f'], 0);
  EXPECT_GT(counts['s'], 0);
  EXPECT_GT(counts['n'], 0);
  options.seed = 8;
  MarkerTrajectories c = clean;
  CorruptionMask mask_c;
  CorruptMarkers(options, &c, &mask_c);
  EXPECT_NE(mask_a, mask_c);
}

}  // namespace
}  // namespace mocapsolve
