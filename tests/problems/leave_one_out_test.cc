// Leave-one-marker-out (problems/marker_solve/leave_one_out.h): on noise-free markers with
// three per bone every left-out marker is still predicted exactly; a marker whose
// observations are moved by a known amount shows that amount and spoils no other; and the
// result does not depend on the number of threads; no sample of a left-out marker reaches its
// own prediction, with or without the per-take offset refinement and the off-body drop; a
// marker off the body in some frames is kept out of the solve that predicts the others.
#include "problems/marker_solve/leave_one_out.h"

#include <gtest/gtest.h>

#include "tests/problems/repair_test_support.h"

namespace mocapsolve {
namespace {

LeaveOneOutOptions Options(int threads) {
  LeaveOneOutOptions options;
  options.frame.solver = SolverKind::kDls;
  options.frame.dls.function_tolerance = 1e-12;
  options.frame.dls.gradient_tolerance = 1e-14;
  options.frame.dls.parameter_tolerance = 1e-14;
  options.frame.dls.max_iterations = 100;
  options.num_threads = threads;
  return options;
}

TEST(LeaveOneOut, NoiseFreeMarkersArePredictedExactly) {
  const testing::DemoTake take = testing::MakeDemoTake(12, 30.0, 7);
  LeaveOneOutReport report;
  ASSERT_TRUE(LeaveOneMarkerOut(take.skeleton, take.markers, take.clean, Options(1), &report).ok());
  ASSERT_EQ(static_cast<int>(report.markers.size()), take.markers.num_markers());
  EXPECT_EQ(report.all.samples, 12 * take.markers.num_markers());
  // Two markers left on a bone still fix it: every prediction is exact up to the solve.
  EXPECT_LT(report.all.max, 1e-4);  // cm.
}

TEST(LeaveOneOut, AMovedMarkerShowsItsOffsetAndSpoilsNoOther) {
  testing::DemoTake take = testing::MakeDemoTake(12, 30.0, 7);
  const int moved = 4;
  const Eigen::Vector3d shift(1.5, -2.0, 0.0);  // cm, |shift| = 2.5.
  for (auto& frame : take.clean) frame[moved] += shift;
  LeaveOneOutOptions options = Options(1);
  LeaveOneOutReport report;
  ASSERT_TRUE(LeaveOneMarkerOut(take.skeleton, take.markers, take.clean, options, &report).ok());
  // Left out, the moved marker is predicted where it belongs: 2.5 cm from its samples.
  EXPECT_NEAR(report.markers[moved].median, 2.5, 0.3);
  // The others are solved with the moved one in, which pulls their bone a little.
  double worst_other = 0.0;
  for (int m = 0; m < take.markers.num_markers(); ++m) {
    if (m != moved) worst_other = std::max(worst_other, report.markers[m].median);
  }
  EXPECT_LT(worst_other, report.markers[moved].median);
  EXPECT_NEAR(report.all.max, report.markers[moved].max, 1e-12);
}

TEST(LeaveOneOut, ResultDoesNotDependOnThreads) {
  testing::DemoTake take = testing::MakeDemoTake(10, 30.0, 3);
  take.clean[3][2] = Eigen::Vector3d::Constant(std::nan(""));  // A missing sample is not scored.
  LeaveOneOutReport one, three;
  ASSERT_TRUE(LeaveOneMarkerOut(take.skeleton, take.markers, take.clean, Options(1), &one).ok());
  ASSERT_TRUE(LeaveOneMarkerOut(take.skeleton, take.markers, take.clean, Options(3), &three).ok());
  EXPECT_EQ(one.markers[2].samples, 9);
  for (size_t m = 0; m < one.markers.size(); ++m) {
    EXPECT_EQ(one.markers[m].samples, three.markers[m].samples);
    EXPECT_EQ(one.markers[m].mean, three.markers[m].mean);
    EXPECT_EQ(one.markers[m].max, three.markers[m].max);
  }
  EXPECT_EQ(one.all.median, three.all.median);
  // Progress counts finished markers, rising to all of them.
  int last = 0;
  ASSERT_TRUE(LeaveOneMarkerOut(take.skeleton, take.markers, take.clean, Options(2), &three,
                                [&](int done) {
                                  EXPECT_GT(done, last);
                                  last = done;
                                })
                  .ok());
  EXPECT_EQ(last, take.markers.num_markers());
}

TEST(LeaveOneOut, ALeftOutMarkersSamplesCannotReachItsPrediction) {
  const testing::DemoTake take = testing::MakeDemoTake(8, 30.0, 7);
  for (int variant : {0, 1, 2}) {
    const int rounds = variant == 1 ? 1 : 0;
    LeaveOneOutOptions options = Options(2);
    if (variant == 2) options.off_body_tolerance = 10.0;  // cm: m's samples moved 30+ cm.
    options.frame.dls = DlsOptions();  // Default tolerances: the test compares two runs, not the truth.
    options.frame.dls.max_iterations = 10;
    options.refine_rounds = rounds;
    options.refine.prior_frames = 5.0;
    options.keep_predictions = true;
    LeaveOneOutReport clean, spoiled;
    ASSERT_TRUE(LeaveOneMarkerOut(take.skeleton, take.markers, take.clean, options, &clean).ok());
    // Marker m's samples moved wildly (a different amount every frame), one sample dropped.
    const int m = 4;
    std::vector<std::vector<Eigen::Vector3d>> moved = take.clean;
    for (size_t f = 0; f < moved.size(); ++f) moved[f][m] += Eigen::Vector3d(30.0 + f, -20.0, 3.0 * f);  // cm.
    moved[6][m] = Eigen::Vector3d::Constant(std::nan(""));
    ASSERT_TRUE(LeaveOneMarkerOut(take.skeleton, take.markers, moved, options, &spoiled).ok());
    ASSERT_EQ(static_cast<int>(spoiled.predicted.size()), take.markers.num_markers());
    // m's predictions are bit for bit those of the clean take (the dropped frame unscored).
    for (size_t f = 0; f < moved.size(); ++f) {
      if (f == 6) {
        EXPECT_FALSE(spoiled.predicted[m][f].allFinite());
        continue;
      }
      EXPECT_EQ(spoiled.predicted[m][f], clean.predicted[m][f]) << "variant " << variant << " frame " << f;
    }
    EXPECT_GT(spoiled.markers[m].median, 20.0);  // Scored against the moved samples.
    // The moved samples do reach the others' predictions, so a leak would be seen (variants 0, 1).
    double other_change = 0.0;
    for (int k = 0; k < take.markers.num_markers(); ++k) {
      if (k == m) continue;
      for (size_t f = 0; f < moved.size(); ++f) {
        other_change = std::max(other_change, (spoiled.predicted[k][f] - clean.predicted[k][f]).norm());
      }
    }
    if (variant == 2) {
      // Off the body by more than the tolerance, m's moved samples are dropped from the others' solves.
      EXPECT_LT(other_change, 1e-6);
    } else {
      EXPECT_GT(other_change, 0.1) << "variant " << variant;  // cm.
    }
  }
}

TEST(LeaveOneOut, AMarkerOffTheBodyIsLeftOutOfTheOthersSolve) {
  testing::DemoTake take = testing::MakeDemoTake(10, 30.0, 7);
  // Marker k lies 2 m off in frames 3-6 (a marker fallen to the floor); everything else is exact.
  const int k = 4;
  for (int f = 3; f <= 6; ++f) take.clean[f][k] += Eigen::Vector3d(200.0, -50.0, 0.0);  // cm.
  const int bone = take.markers.marker(k).attachments[0].joint;
  auto worst_mate = [&](const LeaveOneOutReport& report) {
    double worst = 0.0;
    for (int m = 0; m < take.markers.num_markers(); ++m) {
      if (m != k && take.markers.marker(m).attachments[0].joint == bone) worst = std::max(worst, report.markers[m].max);
    }
    return worst;
  };
  LeaveOneOutOptions options = Options(1);
  LeaveOneOutReport all_in, dropped;
  ASSERT_TRUE(LeaveOneMarkerOut(take.skeleton, take.markers, take.clean, options, &all_in).ok());
  options.off_body_tolerance = 10.0;  // cm.
  ASSERT_TRUE(LeaveOneMarkerOut(take.skeleton, take.markers, take.clean, options, &dropped).ok());
  // Solved with k's samples in, k's bone mates are dragged by it; with them left out, exact.
  EXPECT_GT(worst_mate(all_in), 5.0);
  EXPECT_LT(worst_mate(dropped), 1e-3);
  // k itself is still scored on every sample, its four off the body counted.
  EXPECT_EQ(dropped.markers[k].samples, 10);
  EXPECT_EQ(dropped.markers[k].off_body, 4);
  EXPECT_EQ(dropped.all.off_body, 4);
  EXPECT_EQ(all_in.markers[k].off_body, 0);
  EXPECT_GT(dropped.markers[k].max, 150.0);
}

TEST(LeaveOneOut, SummaryUsesNearestRankPercentiles) {
  std::vector<double> errors = {5, 1, 4, 2, 3, 6, 7, 8, 9, 10};
  const PredictionErrorSummary s = SummarizeErrors(&errors);
  EXPECT_EQ(s.samples, 10);
  EXPECT_DOUBLE_EQ(s.mean, 5.5);
  EXPECT_DOUBLE_EQ(s.median, 5.0);
  EXPECT_DOUBLE_EQ(s.p95, 10.0);
  EXPECT_DOUBLE_EQ(s.max, 10.0);
  std::vector<double> none;
  EXPECT_EQ(SummarizeErrors(&none).samples, 0);
}

TEST(LeaveOneOut, BadInputIsAnError) {
  const testing::DemoTake take = testing::MakeDemoTake(3, 30.0, 7);
  LeaveOneOutReport report;
  EXPECT_FALSE(LeaveOneMarkerOut(take.skeleton, take.markers, {}, Options(1), &report).ok());
  auto short_frame = take.clean;
  short_frame[1].pop_back();
  EXPECT_FALSE(LeaveOneMarkerOut(take.skeleton, take.markers, short_frame, Options(1), &report).ok());
  LeaveOneOutOptions negative = Options(1);
  negative.off_body_tolerance = -1.0;
  EXPECT_FALSE(LeaveOneMarkerOut(take.skeleton, take.markers, take.clean, negative, &report).ok());
}

}  // namespace
}  // namespace mocapsolve
