// The small-error recipe and its scoring (small_error_evaluation.h) on the demo walk.
#include "problems/marker_repair/small_error_evaluation.h"

#include <gtest/gtest.h>

#include "tests/problems/repair_test_support.h"

namespace mocapsolve {
namespace {

using Observations = std::vector<std::vector<Eigen::Vector3d>>;

TEST(SmallErrorEvaluation, RecipeMovesSamplesByItsSizesAndNoiseLeavesTheDrawsAlone) {
  const testing::DemoTake take = testing::MakeDemoTake(300, 60.0, 5);
  const SmallErrorRecipe recipe = DefaultSmallErrorRecipe(0.01);  // The demo skeleton is in cm.
  EXPECT_DOUBLE_EQ(recipe.jump_min, 1.0);
  EXPECT_DOUBLE_EQ(recipe.jump_max, 4.0);
  Observations damaged = take.clean;
  SampleFlags hurt;
  AddSmallErrors(recipe, &damaged, &hurt);
  const int nf = static_cast<int>(damaged.size()), nm = take.markers.num_markers();
  int moved = 0;
  for (int f = 0; f < nf; ++f) {
    for (int m = 0; m < nm; ++m) {
      const double d = (damaged[f][m] - take.clean[f][m]).norm();
      if (!hurt[f][m]) {
        EXPECT_EQ(d, 0.0) << f << " " << m;
        continue;
      }
      ++moved;
      EXPECT_GE(d, 1.0 - 1e-12);  // Jumps of 1-4 cm, jitter of at least 1 cm (3-sigma bound: ~6 cm).
      EXPECT_LE(d, 8.0);
      EXPECT_TRUE(f >= 5 && f < nf - 5) << f;
    }
  }
  EXPECT_GT(moved, 12);  // At least one sample per jump, most runs longer.
  // White noise comes from its own generator: the damage is the same sample for sample.
  SmallErrorRecipe noisy = recipe;
  noisy.white_noise = 0.1;
  Observations with_noise = take.clean;
  AddWhiteNoise(noisy, &with_noise);
  double squares = 0.0;
  for (int f = 0; f < nf; ++f) {
    for (int m = 0; m < nm; ++m) squares += (with_noise[f][m] - take.clean[f][m]).squaredNorm();
  }
  EXPECT_NEAR(std::sqrt(squares / (3.0 * nf * nm)), 0.1, 0.01);  // The per-axis sigma asked for.
  SampleFlags hurt_noisy;
  AddSmallErrors(noisy, &with_noise, &hurt_noisy);
  EXPECT_EQ(hurt_noisy, hurt);
}

TEST(SmallErrorEvaluation, ScoresAddUp) {
  const testing::DemoTake take = testing::MakeDemoTake(240, 60.0, 5);
  SmallErrorRecipe recipe = DefaultSmallErrorRecipe(0.01, 1.0);
  SmallErrorScore score;
  const Status status = EvaluateSmallErrors(take.skeleton, take.markers, take.clean,
                                            testing::DemoRepairOptions(ReferenceKind::kTracker), recipe, 2, &score);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(score.seeds.size(), 2u);
  long damaged = 0, flagged = 0, found = 0, own = 0;
  for (const SmallErrorSeedScore& s : score.seeds) {
    EXPECT_LE(s.true_positive, std::min(s.damaged, s.flagged));
    EXPECT_LE(s.own_damaged, s.own);
    EXPECT_LE(s.own, s.flagged);
    damaged += s.damaged, flagged += s.flagged, found += s.true_positive, own += s.own;
  }
  EXPECT_EQ(score.seeds[0].seed, 1u);
  EXPECT_EQ(score.seeds[1].seed, 2u);
  EXPECT_EQ(score.damaged, damaged);
  EXPECT_EQ(score.flagged, flagged);
  EXPECT_EQ(score.true_positive, found);
  EXPECT_EQ(score.own, own);
  EXPECT_GT(score.damaged, 0);
  EXPECT_DOUBLE_EQ(score.Recall(), double(found) / damaged);
  EXPECT_GE(score.PrecisionWithoutOwn(), 0.0);
  EXPECT_LE(score.PrecisionWithoutOwn(), 1.0);
}

}  // namespace
}  // namespace mocapsolve
