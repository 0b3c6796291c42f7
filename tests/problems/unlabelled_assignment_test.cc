// Unlabelled points labelled (issue 16 item 3), on crafted cases: a hand-made residual
// model (predictions moving at constant velocity, cm) for the assignment rules, then the
// whole repair on the demo walk: a dropout whose samples appear as an unlabelled point is
// restored, a ghost beside a present marker and a point far from every prediction are not
// assigned, two points near two missing markers go one to one.
#include "problems/marker_repair/unlabelled_assignment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "problems/marker_repair/marker_repair.h"
#include "tests/problems/repair_test_support.h"

namespace mocapsolve {
namespace {

using Observations = std::vector<std::vector<Eigen::Vector3d>>;
const Eigen::Vector3d kNan = Eigen::Vector3d::Constant(std::nan(""));

// #M markers 10 cm apart on x moving at 0.5 cm/frame along y; every marker's sample is its
// prediction plus `offset` (its typical residual is absorbed in P); gates 2 cm (the floor:
// median deviation 0.2 + 6 x 0.1 = 0.8), step gates 0.5 cm.
struct Crafted {
  MarkerResidualModel model;
  MarkerTrajectories x;
  UnlabelledPoints unlabelled;
  UnlabelledAssignmentOptions options;

  Crafted(int frames, int markers, int tracks) {
    std::vector<std::string> labels;
    for (int m = 0; m < markers; ++m) labels.push_back("M" + std::to_string(m));
    x = MarkerTrajectories(labels, frames);
    model.predicted.assign(frames, std::vector<Eigen::Vector3d>(markers));
    for (int f = 0; f < frames; ++f) {
      for (int m = 0; m < markers; ++m) {
        model.predicted[f][m] = Eigen::Vector3d(10.0 * m, 0.5 * f, 100.0);
        x.SetSample(f, m, Truth(f, m));
      }
    }
    model.median_deviation.assign(markers, 0.2);
    model.scale.assign(markers, 0.1);
    model.step_gate.assign(markers, 0.5);
    for (int k = 0; k < tracks; ++k) unlabelled.names.push_back("*" + std::to_string(50 + k));
    unlabelled.points.assign(frames, std::vector<Eigen::Vector3d>(tracks, kNan));
    options.mads = 6.0;
    options.min_distance = 2.0;
    options.max_distance = 5.0;
    options.min_frames = 3;
  }
  Eigen::Vector3d Truth(int f, int m) const { return model.predicted[f][m] + Eigen::Vector3d(0.3, -0.2, 0.1); }
  // Marker m's samples of frames [first, last] leave its label for track k.
  void Unlabel(int m, int first, int last, int k) {
    for (int f = first; f <= last; ++f) {
      unlabelled.points[f][k] = x.position(f, m);
      x.SetMissing(f, m);
    }
  }
  std::vector<UnlabelledAssignment> Assign() { return AssignUnlabelledPoints(model, unlabelled, options, &x); }
};

TEST(UnlabelledAssignment, DropoutThatAppearsAsAnUnlabelledPointIsRestored) {
  Crafted c(60, 4, 1);
  c.Unlabel(2, 20, 39, 0);
  const auto assigned = c.Assign();
  ASSERT_EQ(assigned.size(), 1u);
  EXPECT_EQ(assigned[0].marker, 2);
  EXPECT_EQ(assigned[0].track, 0);
  EXPECT_EQ(assigned[0].first, 20);
  EXPECT_EQ(assigned[0].last, 39);
  EXPECT_NEAR(assigned[0].mean_distance, Eigen::Vector3d(0.3, -0.2, 0.1).norm(), 1e-12);
  for (int f = 20; f <= 39; ++f) {
    ASSERT_TRUE(c.x.valid(f, 2)) << f;
    EXPECT_EQ(c.x.position(f, 2), c.Truth(f, 2)) << f;  // Bit for bit: the point itself.
  }
}

TEST(UnlabelledAssignment, GhostBesideAPresentMarkerIsNotAssigned) {
  Crafted c(60, 4, 1);
  // Marker 1 is present; marker 2 missing. The "ghost" sits 1 cm from marker 1's
  // prediction, 9 cm from marker 2's: beyond every gate of 2 but 1's.
  for (int f = 10; f < 30; ++f) c.x.SetMissing(f, 2);
  for (int f = 10; f < 30; ++f) c.unlabelled.points[f][0] = c.model.predicted[f][1] + Eigen::Vector3d(1.0, 0, 0);
  EXPECT_TRUE(c.Assign().empty());
  // Nearer to the missing marker than its gate, but fitting the present one better: a
  // ghost of the present marker, still not assigned. Gates of 4 cm: the point at 2.5 cm
  // from marker 1 and 3.5 cm from marker 2, to which it would be admissible.
  Crafted d(60, 4, 1);
  d.model.predicted.assign(60, std::vector<Eigen::Vector3d>(4));
  for (int f = 0; f < 60; ++f) {
    for (int m = 0; m < 4; ++m) d.model.predicted[f][m] = Eigen::Vector3d(6.0 * m, 0.5 * f, 100.0);
  }
  d.options.min_distance = 4.0;
  for (int f = 10; f < 30; ++f) d.x.SetMissing(f, 2);
  for (int f = 10; f < 30; ++f) d.unlabelled.points[f][0] = d.model.predicted[f][1] + Eigen::Vector3d(2.5, 0, 0);
  EXPECT_TRUE(d.Assign().empty());
}

TEST(UnlabelledAssignment, TwoPointsNearTwoMissingMarkersGoOneToOne) {
  // Markers 1 and 2 missing over frames 20-39 with 1.5 cm between their predictions; their
  // points come as tracks in the other order, each 0.9 cm (A) and 1.1 cm (B) off its
  // prediction along the line between them: point A lies nearer B's prediction (0.6 cm)
  // than its own, so matching the nearest pair first would give it to B and leave A with
  // nothing within its gate. The one-to-one optimum gives each its own.
  Crafted c(60, 4, 2);
  for (int f = 0; f < 60; ++f) {
    c.model.predicted[f][2] = c.model.predicted[f][1] + Eigen::Vector3d(1.5, 0, 0);
  }
  for (int f = 0; f < 60; ++f) {
    c.x.SetSample(f, 1, c.model.predicted[f][1] + Eigen::Vector3d(0.9, 0, 0));
    c.x.SetSample(f, 2, c.model.predicted[f][2] + Eigen::Vector3d(1.1, 0, 0));
  }
  Observations truth(60, std::vector<Eigen::Vector3d>(4));
  for (int f = 0; f < 60; ++f) {
    for (int m = 0; m < 4; ++m) truth[f][m] = c.x.position(f, m);
  }
  c.Unlabel(1, 20, 39, 1);
  c.Unlabel(2, 20, 39, 0);
  const auto assigned = c.Assign();
  ASSERT_EQ(assigned.size(), 2u);
  EXPECT_EQ(assigned[0].marker, 1);
  EXPECT_EQ(assigned[0].track, 1);
  EXPECT_EQ(assigned[1].marker, 2);
  EXPECT_EQ(assigned[1].track, 0);
  for (int f = 20; f <= 39; ++f) {
    EXPECT_EQ(c.x.position(f, 1), truth[f][1]) << f;
    EXPECT_EQ(c.x.position(f, 2), truth[f][2]) << f;
  }
}

TEST(UnlabelledAssignment, PointFarFromEveryPredictionIsNotAssigned) {
  Crafted c(60, 4, 1);
  for (int f = 10; f < 50; ++f) c.x.SetMissing(f, 3);
  for (int f = 10; f < 50; ++f) c.unlabelled.points[f][0] = c.model.predicted[f][3] + Eigen::Vector3d(0, 0, 8.0);
  EXPECT_TRUE(c.Assign().empty());
  for (int f = 10; f < 50; ++f) EXPECT_FALSE(c.x.valid(f, 3));
}

TEST(UnlabelledAssignment, ContinuityDecidesShortRunsAndJumps) {
  // A lone point for two frames inside a gap continues nothing: not assigned. One frame
  // that bridges the marker's observed track is. A run whose first point jumps 1.5 cm away
  // from the observed sample before it (step gate 0.5, continuity 1 cm) is not.
  Crafted c(60, 4, 3);
  for (int f = 10; f < 20; ++f) c.x.SetMissing(f, 0);
  c.unlabelled.points[14][0] = c.Truth(14, 0);
  c.unlabelled.points[15][0] = c.Truth(15, 0);
  c.Unlabel(1, 30, 30, 1);
  for (int f = 40; f < 50; ++f) c.x.SetMissing(f, 3);
  for (int f = 40; f < 50; ++f) c.unlabelled.points[f][2] = c.Truth(f, 3) + Eigen::Vector3d(0, 0, 1.5);
  const auto assigned = c.Assign();
  ASSERT_EQ(assigned.size(), 1u);
  EXPECT_EQ(assigned[0].marker, 1);
  EXPECT_EQ(assigned[0].first, 30);
  EXPECT_EQ(assigned[0].last, 30);
  // The same two lone frames with min_frames 2 are kept.
  Crafted d(60, 4, 1);
  for (int f = 10; f < 20; ++f) d.x.SetMissing(f, 0);
  d.unlabelled.points[14][0] = d.Truth(14, 0);
  d.unlabelled.points[15][0] = d.Truth(15, 0);
  d.options.min_frames = 2;
  EXPECT_EQ(d.Assign().size(), 1u);
}

TEST(UnlabelledAssignment, ObservedSamplesAreNeverOverwritten) {
  Crafted c(30, 3, 1);
  for (int f = 0; f < 30; ++f) c.unlabelled.points[f][0] = c.Truth(f, 1) + Eigen::Vector3d(0.2, 0, 0);
  EXPECT_TRUE(c.Assign().empty());
  for (int f = 0; f < 30; ++f) EXPECT_EQ(c.x.position(f, 1), c.Truth(f, 1));
}

TEST(MinimumCostAssignment, MatchesExhaustiveSearch) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int rows = 1 + trial % 4, columns = rows + (trial / 4) % 3;
    std::vector<std::vector<double>> cost(rows, std::vector<double>(columns));
    for (auto& row : cost) {
      for (double& v : row) v = uniform(rng);
    }
    const std::vector<int> column = MinimumCostAssignment(cost);
    double found = 0.0;
    std::vector<int> used;
    for (int r = 0; r < rows; ++r) {
      ASSERT_GE(column[r], 0);
      found += cost[r][column[r]];
      used.push_back(column[r]);
    }
    std::sort(used.begin(), used.end());
    EXPECT_TRUE(std::adjacent_find(used.begin(), used.end()) == used.end());  // One to one.
    // Every injection of rows into columns: permutations of the columns, first `rows`.
    std::vector<int> order(columns);
    std::iota(order.begin(), order.end(), 0);
    double best = std::numeric_limits<double>::infinity();
    do {
      double sum = 0.0;
      for (int r = 0; r < rows; ++r) sum += cost[r][order[r]];
      best = std::min(best, sum);
    } while (std::next_permutation(order.begin(), order.end()));
    EXPECT_NEAR(found, best, 1e-12) << trial;  // Sums of a few numbers in [0, 1].
  }
}

// The whole repair on the demo walk (cm, 1 mm noise): marker a drops out for frames 40-69
// and its samples come back as the unlabelled point "*52"; "*53" is a ghost 1.5 cm from
// a present marker; "*54" sits 15 cm from every marker.
TEST(UnlabelledAssignment, RepairRestoresADropoutFromAnUnlabelledPoint) {
  const testing::DemoTake take = testing::MakeDemoTake(160, 60.0, 5);
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 0.1);
  Observations truth = take.clean;
  for (auto& frame : truth) {
    for (Eigen::Vector3d& p : frame) p += Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  }
  const int a = take.markers.FindMarker("LeftLeg_0"), b = take.markers.FindMarker("RightArm_1");
  ASSERT_TRUE(a >= 0 && b >= 0);
  Observations observed = truth;
  UnlabelledPoints unlabelled;
  unlabelled.names = {"*52", "*53", "*54"};
  unlabelled.points.assign(truth.size(), std::vector<Eigen::Vector3d>(3, kNan));
  for (int f = 40; f < 70; ++f) {
    unlabelled.points[f][0] = truth[f][a];
    observed[f][a] = kNan;
  }
  for (int f = 80; f < 120; ++f) unlabelled.points[f][1] = truth[f][b] + Eigen::Vector3d(1.5, 0, 0);
  for (int f = 0; f < 160; ++f) unlabelled.points[f][2] = truth[f][a] + Eigen::Vector3d(0, 15.0, 0);
  RepairOptions options = testing::DemoRepairOptions(ReferenceKind::kTracker);
  Observations repaired;
  Motion motion;
  RepairReport report;
  ASSERT_TRUE(RepairMarkers(take.skeleton, take.markers, observed, unlabelled, options, &repaired, &motion, &report)
                  .ok());
  ASSERT_EQ(report.unlabelled.size(), 1u);
  EXPECT_EQ(report.unlabelled[0].marker, a);
  EXPECT_EQ(report.unlabelled[0].track, 0);
  EXPECT_EQ(report.unlabelled[0].first, 40);
  EXPECT_EQ(report.unlabelled[0].last, 69);
  for (int f = 40; f < 70; ++f) EXPECT_EQ(repaired[f][a], truth[f][a]) << f;  // The point itself.
  bool reported = false;
  for (const RepairInterval& i : report.detected) reported |= i.what == "unlabelled" && i.marker == a;
  EXPECT_TRUE(reported);
  // Without the points (or with assignment off) the gap is refilled from the reference.
  options.assign_unlabelled = false;
  Observations refilled;
  ASSERT_TRUE(RepairMarkers(take.skeleton, take.markers, observed, unlabelled, options, &refilled, &motion, &report)
                  .ok());
  EXPECT_TRUE(report.unlabelled.empty());
  EXPECT_NE(refilled[55][a], truth[55][a]);
}

}  // namespace
}  // namespace mocapsolve
