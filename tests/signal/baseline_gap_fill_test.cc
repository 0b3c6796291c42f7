// The comparison fills of issue 4's evaluation on paths where each is exact: linear on
// straight lines, the polynomial on straight lines too (its one-sided velocities are
// exact there), PCA on low-rank data it can explain; the ends are held; a marker
// missing all take stays missing.
#include "signal/baseline_gap_fill.h"

#include <cmath>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

MarkerTrajectories Paths(int frames, const std::function<Eigen::Vector3d(int, int)>& path, int markers) {
  std::vector<std::string> labels;
  for (int m = 0; m < markers; ++m) labels.push_back("M" + std::to_string(m));
  MarkerTrajectories x(labels, frames);
  for (int f = 0; f < frames; ++f) {
    for (int m = 0; m < markers; ++m) x.SetSample(f, m, path(f, m));
  }
  return x;
}

Eigen::Vector3d Line(int f, int m) { return Eigen::Vector3d(1.0 + m, 0.5 * f, -0.25 * f + m); }

TEST(BaselineGapFill, LinearAndPolynomialAreExactOnStraightLines) {
  for (int method = 0; method < 2; ++method) {
    MarkerTrajectories x = Paths(50, Line, 2);
    for (int f = 10; f < 30; ++f) x.SetMissing(f, 1);
    x.SetMissing(25, 0);  // A one-frame gap.
    const int filled = method == 0 ? FillGapsLinear(&x) : FillGapsPolynomial(&x);
    EXPECT_EQ(filled, 21);
    for (int f = 0; f < 50; ++f) {
      for (int m = 0; m < 2; ++m) {
        ASSERT_TRUE(x.valid(f, m));
        EXPECT_LT((x.position(f, m) - Line(f, m)).norm(), 1e-12) << method << " " << f << " " << m;
      }
    }
  }
}

TEST(BaselineGapFill, EndsAreHeldAndAMarkerMissingAllTakeStaysMissing) {
  MarkerTrajectories x = Paths(20, Line, 2);
  for (int f = 0; f < 5; ++f) x.SetMissing(f, 0);
  for (int f = 15; f < 20; ++f) x.SetMissing(f, 0);
  for (int f = 0; f < 20; ++f) x.SetMissing(f, 1);
  EXPECT_EQ(FillGapsLinear(&x), 10);
  for (int f = 0; f < 5; ++f) EXPECT_EQ(x.position(f, 0), Line(5, 0));
  for (int f = 15; f < 20; ++f) EXPECT_EQ(x.position(f, 0), Line(14, 0));
  for (int f = 0; f < 20; ++f) EXPECT_FALSE(x.valid(f, 1));
}

TEST(BaselineGapFill, PcaRecoversAMarkerFromItsCorrelationsWithTheOthers) {
  // Six markers whose coordinates are combinations of two non-linear signals (rank 2
  // about the mean): a gap in one is predictable from the others, not from its own ends.
  auto path = [](int f, int m) {
    const double a = std::sin(0.21 * f), b = std::cos(0.13 * f) * std::sin(0.05 * f);
    return Eigen::Vector3d(m + a * (1 + m), b * (2 - m) + 0.5 * a, 3 * a - b * m);
  };
  MarkerTrajectories x = Paths(200, path, 6);
  for (int f = 60; f < 110; ++f) x.SetMissing(f, 2);
  for (int f = 150; f < 160; ++f) x.SetMissing(f, 4);
  MarkerTrajectories linear = x;
  FillGapsLinear(&linear);
  PcaFillOptions options;
  EXPECT_EQ(FillGapsPca(options, &x), 60);
  double worst = 0.0, worst_linear = 0.0;
  for (int f = 60; f < 110; ++f) {
    worst = std::max(worst, (x.position(f, 2) - path(f, 2)).norm());
    worst_linear = std::max(worst_linear, (linear.position(f, 2) - path(f, 2)).norm());
  }
  EXPECT_GT(worst_linear, 0.5);  // The gap is long enough to matter.
  EXPECT_LT(worst, 1e-9);        // Exact: the complete frames span the data.
}

}  // namespace
}  // namespace mocapsolve
