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

// The kinds of issue 16: a swap that begins inside a gap, jitter of 0.5-1.5 x its size,
// a ghost at a constant offset; and turning them on leaves the earlier kinds' damage of
// the same seed as it was.
TEST(MarkerCorruption, SwapsInGapsJitterAndGhosts) {
  CorruptionOptions options;
  options.seed = 3;
  options.gaps = options.cluster_gaps = options.swaps = options.noisy_markers = 2;
  options.cluster_radius = 15.0;
  options.fly_off_distance = 30.0;
  options.swap_radius = 12.0;
  options.noise_sigma = 2.0;
  const MarkerTrajectories clean = Clean(400);
  MarkerTrajectories before = clean;
  CorruptionMask mask_before;
  CorruptMarkers(options, &before, &mask_before);
  options.swaps_in_gaps = 1;
  options.jitter_markers = 2;
  options.jitter_distance = 2.0;
  options.ghosts = 2;
  options.ghost_distance = 3.0;
  MarkerTrajectories after = clean;
  CorruptionMask mask;
  CorruptMarkers(options, &after, &mask);
  int counts[256] = {0};
  Eigen::Vector3d ghost_offset = Eigen::Vector3d::Zero();
  for (int f = 0; f < 400; ++f) {
    for (int m = 0; m < 6; ++m) {
      if (mask_before[f][m] != 0 && mask_before[f][m] != 's') {
        EXPECT_EQ(mask[f][m], mask_before[f][m]);
      }
      const char kind = mask[f][m];
      ++counts[static_cast<unsigned char>(kind)];
      if (kind == 'j') {
        const double size = (after.position(f, m) - clean.position(f, m)).norm();
        EXPECT_GE(size, 1.0);
        EXPECT_LE(size, 3.0);
      }
      if (kind == 'h') {
        const Eigen::Vector3d offset = after.position(f, m) - clean.position(f, m);
        EXPECT_NEAR(offset.norm(), 3.0, 1e-12);
        if (f > 0 && mask[f - 1][m] == 'h') {
          EXPECT_LT((offset - ghost_offset).norm(), 1e-12);
        }
        ghost_offset = offset;
      }
    }
  }
  EXPECT_GT(counts['j'], 0);
  EXPECT_GT(counts['h'], 0);
  // A swap that begins inside a gap: some marker is 'g' and then, without a clean frame
  // between, 's'.
  bool swap_after_gap = false;
  for (int m = 0; m < 6; ++m) {
    for (int f = 1; f < 400; ++f) swap_after_gap = swap_after_gap || (mask[f - 1][m] == 'g' && mask[f][m] == 's');
  }
  EXPECT_TRUE(swap_after_gap);
  EXPECT_EQ(DamageKindIndex('h'), 5);
  EXPECT_EQ(DamageKindIndex(0), -1);
}

// Unlabelled runs: drawn after every other kind, so a seed's other damage is as it was;
// each run's samples leave the marker for their own track, exactly as they were.
TEST(MarkerCorruption, UnlabelledRunsMoveSamplesToTracks) {
  CorruptionOptions options;
  options.seed = 5;
  options.cluster_radius = 15.0;
  options.fly_off_distance = 30.0;
  options.swap_radius = 12.0;
  options.noise_sigma = 2.0;
  options.ghosts = 1;
  options.ghost_distance = 3.0;
  const MarkerTrajectories clean = Clean(300);
  MarkerTrajectories before = clean, after = clean;
  CorruptionMask mask_before, mask;
  UnlabelledDamage none;
  CorruptMarkers(options, &before, &mask_before, &none);
  EXPECT_EQ(none.tracks.num_markers(), 0);
  options.unlabels = 3;
  options.unlabel_length = 20;
  UnlabelledDamage unlabelled;
  CorruptMarkers(options, &after, &mask, &unlabelled);
  ASSERT_EQ(unlabelled.tracks.num_markers(), 3);
  ASSERT_EQ(unlabelled.source.size(), 3u);
  EXPECT_EQ(unlabelled.tracks.label(0), "*1");
  EXPECT_EQ(unlabelled.tracks.num_frames(), 300);
  int moved = 0;
  for (int f = 0; f < 300; ++f) {
    for (int m = 0; m < 6; ++m) {
      if (mask[f][m] != 'u') {
        EXPECT_EQ(mask[f][m], mask_before[f][m]);
        if (before.valid(f, m)) {
          EXPECT_EQ(after.position(f, m), before.position(f, m));
        }
        continue;
      }
      EXPECT_EQ(mask_before[f][m], 0);
      EXPECT_FALSE(after.valid(f, m));
      bool found = false;
      for (int k = 0; k < 3; ++k) {
        if (unlabelled.source[k] == m && unlabelled.tracks.valid(f, k)) {
          found |= unlabelled.tracks.position(f, k) == clean.position(f, m);
        }
      }
      EXPECT_TRUE(found) << f << " " << m;
      ++moved;
    }
  }
  EXPECT_GT(moved, 0);
  EXPECT_EQ(DamageKindIndex('u'), 6);
}

}  // namespace
}  // namespace mocapsolve
