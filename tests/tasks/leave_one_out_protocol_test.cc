// The leave-one-out protocols (tasks/leave_one_out_protocol.h) through RunEvaluate, on the
// demo walk with 3 synthetic markers per bone: under cross_take and under time_split, moving
// one marker's samples on the scored frames leaves its own predictions bit for bit unchanged
// (no leak), while under time_split moving them in the first half (the fit's frames) does
// change them (the split is where the header says).
#include "tasks/leave_one_out_protocol.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tasks/evaluate_task.h"
#include "tests/problems/repair_test_support.h"

namespace mocapsolve {
namespace {

constexpr int kFrames = 40;

// The demo take as a subject and a marker file read against it (cm, the skeleton's axes),
// marker `moved` shifted by `shift` (cm) on frames [first, last).
MarkerTake DemoMarkerTake(const testing::DemoTake& demo, int moved, int first, int last,
                          const Eigen::Vector3d& shift) {
  Subject subject;
  subject.skeleton = demo.skeleton;
  subject.markers = demo.markers;
  std::vector<std::string> labels;
  for (int m = 0; m < demo.markers.num_markers(); ++m) labels.push_back(demo.markers.label(m));
  MarkerTrajectories file(labels, kFrames);
  file.unit = demo.skeleton.unit();
  file.frame_rate = 30.0;
  for (int f = 0; f < kFrames; ++f) {
    for (int m = 0; m < demo.markers.num_markers(); ++m) {
      const bool shifted = m == moved && f >= first && f < last;
      file.SetSample(f, m, demo.clean[f][m] + (shifted ? Eigen::Vector3d(shift + f * Eigen::Vector3d(0.5, 0, 0)) : Eigen::Vector3d::Zero()));
    }
  }
  MarkerTake take;
  EXPECT_TRUE(TakeForSubject(subject, std::move(file), "demo.trc", &take).ok());
  return take;
}

// Predictions of marker `label` over the scored frames.
std::vector<Eigen::Vector3d> Predictions(const MarkerTake& take, const std::string& protocol,
                                         const std::string& label,
                                         const SkeletonFitSettings& fit = SkeletonFitSettings()) {
  EvaluateConfig config;
  config.fit = fit;
  config.method = "leave_one_out";
  config.evaluate.protocol = protocol;
  config.solver.num_threads = 2;
  config.keep_predictions = true;
  EvaluateResult result;
  const Status status = RunEvaluate(take, config, nullptr, &result);
  EXPECT_TRUE(status.ok()) << status.message();
  for (size_t m = 0; m < result.leave_one_out_labels.size(); ++m) {
    if (result.leave_one_out_labels[m] == label) return result.leave_one_out.predicted[m];
  }
  ADD_FAILURE() << label << " not scored";
  return {};
}

bool SameBits(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  if (a.size() != b.size()) return false;
  for (size_t f = 0; f < a.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (!(a[f][k] == b[f][k]) && !(std::isnan(a[f][k]) && std::isnan(b[f][k]))) return false;
    }
  }
  return true;
}

TEST(LeaveOneOutProtocol, ScoredSamplesOfTheLeftOutMarkerCannotReachItsPrediction) {
  const testing::DemoTake demo = testing::MakeDemoTake(kFrames, 30.0, 7);
  const int m = 4;
  const std::string label = demo.markers.label(m);
  const Eigen::Vector3d shift(6.0, -4.0, 2.0);  // cm, plus 0.5 cm a frame.
  const MarkerTake clean = DemoMarkerTake(demo, m, 0, 0, shift);
  // cross_take: every frame scored.
  EXPECT_TRUE(SameBits(Predictions(clean, "cross_take", label),
                       Predictions(DemoMarkerTake(demo, m, 0, kFrames, shift), "cross_take", label)));
  // time_split: the second half scored, the subject fitted on the first.
  const std::vector<Eigen::Vector3d> split = Predictions(clean, "time_split", label);
  ASSERT_EQ(static_cast<int>(split.size()), kFrames / 2);
  EXPECT_TRUE(SameBits(split, Predictions(DemoMarkerTake(demo, m, kFrames / 2, kFrames, shift), "time_split", label)));
  // The first half is the fit's: moving the marker there moves its fitted offset.
  EXPECT_FALSE(SameBits(split, Predictions(DemoMarkerTake(demo, m, 0, kFrames / 2, shift), "time_split", label)));
}

// time_split fits its first half with the fit settings given (fit_skeleton's options, as
// `evaluate` reads them), not always fit_skeleton's defaults: a fit on every 5th frame of
// the half predicts otherwise.
TEST(LeaveOneOutProtocol, TheTimeSplitFitsWithTheSettingsGiven) {
  const testing::DemoTake demo = testing::MakeDemoTake(kFrames, 30.0, 7);
  const MarkerTake take = DemoMarkerTake(demo, 0, 0, 0, Eigen::Vector3d::Zero());
  const std::string label = demo.markers.label(4);
  SkeletonFitSettings sparse;
  sparse.fit_frame_step = 5;
  EXPECT_FALSE(SameBits(Predictions(take, "time_split", label), Predictions(take, "time_split", label, sparse)));
}

TEST(LeaveOneOutProtocol, TooShortATakeAndAnUnknownProtocolAreErrors) {
  const testing::DemoTake demo = testing::MakeDemoTake(kFrames, 30.0, 7);
  MarkerTake take = DemoMarkerTake(demo, 0, 0, 0, Eigen::Vector3d::Zero());
  MarkerTake scored;
  JsonObject report;
  EXPECT_EQ(LeaveOneOutProtocolTake(take, "same_take", SolverSettings(), SkeletonFitSettings(), &scored, &report).message(),
            "--protocol: expected cross_take or time_split, got 'same_take'");
  take.trajectories = TrajectoryFrames(take.trajectories, 0, 30);
  EXPECT_EQ(LeaveOneOutProtocolTake(take, "time_split", SolverSettings(), SkeletonFitSettings(), &scored, &report).message(),
            "demo.trc: --protocol=time_split needs at least 40 frames (has 30)");
}

}  // namespace
}  // namespace mocapsolve
