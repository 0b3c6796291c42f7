// EXPAND by cubic Cardinal splines: interpolation, polynomial reproduction, the ends.
#include "signal/cardinal_spline.h"

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

Signal Samples(int rows, double (*f)(double)) {
  Signal signal(rows, 1);
  for (int i = 0; i < rows; ++i) signal(i, 0) = f(i);
  return signal;
}

TEST(CardinalSpline, KeepsTheSamplesAndFillsMidpoints) {
  const Signal coarse = Samples(6, [](double x) { return x * x; });
  Signal fine;
  ExpandMidpoints(coarse, 11, 0.0, &fine);
  ASSERT_EQ(fine.rows(), 11);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(fine(2 * k, 0), coarse(k, 0));
  ExpandMidpoints(coarse, 12, 0.0, &fine);  // Even length: one extrapolated sample.
  ASSERT_EQ(fine.rows(), 12);
}

TEST(CardinalSpline, CatmullRomMidpointsReproduceCubicsInside) {
  // (-1, 9, 9, -1) / 16 is exact for cubics: tension 0, where all four samples exist.
  const Signal coarse =
      Samples(8, [](double x) { return 0.5 * x * x * x - 2.0 * x * x + x - 3.0; });
  Signal fine;
  ExpandMidpoints(coarse, 15, 0.0, &fine);
  for (int k = 1; k + 2 < 8; ++k) {
    const double x = k + 0.5;
    EXPECT_NEAR(fine(2 * k + 1, 0), 0.5 * x * x * x - 2.0 * x * x + x - 3.0, 1e-12) << k;
  }
}

TEST(CardinalSpline, LinesAreExactEverywhereForAnyTension) {
  const Signal coarse = Samples(5, [](double x) { return 4.0 - 1.5 * x; });
  for (double tension : {0.0, 0.3, 1.0}) {
    for (int rows : {9, 10}) {
      Signal fine;
      ExpandMidpoints(coarse, rows, tension, &fine);
      for (int i = 0; i < rows; ++i) EXPECT_NEAR(fine(i, 0), 4.0 - 0.75 * i, 1e-13) << i;
    }
  }
}

TEST(CardinalSpline, ExpandAndCombineIsFused) {
  const Signal coarse = Samples(4, [](double x) { return x * x; });
  const Signal other = Samples(8, [](double x) { return 1.0 / (1.0 + x); });
  Signal expanded, combined;
  ExpandMidpoints(coarse, 8, 0.25, &expanded);
  ExpandAndCombine(coarse, 0.25, -2.0, other, 3.0, &combined);
  EXPECT_LT((combined - (-2.0 * expanded + 3.0 * other)).cwiseAbs().maxCoeff(), 1e-14);
}

}  // namespace
}  // namespace mocapsolve
