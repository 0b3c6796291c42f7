// LiveTracker (problems/marker_solve/live_tracker.h): frame by frame on the demo walk's
// noise-free synthetic markers, the poses are recovered; with markers occluded the
// constant-velocity prediction keeps the pose closer to the truth than leaving them out.
#include "problems/marker_solve/live_tracker.h"

#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

std::vector<Eigen::Vector3d> Observe(const Skeleton& skeleton, const MarkerSet& markers, const Pose& pose) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose, &fk);
  std::vector<Eigen::Vector3d> observed;
  for (int m = 0; m < markers.num_markers(); ++m) observed.push_back(markers.Position(m, fk));
  return observed;
}

// Largest joint position error over the frames, tracking with `predict_frames`, the
// markers of `hidden` joints occluded in frames [10, 20).
double WorstJointError(int predict_frames, const std::vector<int>& hidden, LiveTrackReport* last) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::mt19937 rng(3);
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, rng());
  const Motion truth = MakeDemoWalk(skeleton, 30, 30.0);
  MarkerSolveOptions options;
  options.prior_rotation_weight = 0.05;  // As a live solve has: a pull toward the previous pose.
  LiveTracker tracker(skeleton, markers, options, predict_frames);
  FkData solved(skeleton), expected(skeleton);
  double worst = 0.0;
  for (int f = 0; f < truth.num_frames(); ++f) {
    std::vector<Eigen::Vector3d> observed = Observe(skeleton, markers, truth.frames[f]);
    for (int m = 0; m < markers.num_markers() && f >= 10 && f < 20; ++m) {
      for (int joint : hidden) {
        if (markers.marker(m).attachments[0].joint == joint) observed[m].setConstant(std::nan(""));
      }
    }
    Pose pose;
    EXPECT_TRUE(tracker.Track(observed, &pose, last).ok());
    EXPECT_TRUE(last->solved) << f;
    ForwardKinematics(skeleton, pose, &solved);
    ForwardKinematics(skeleton, truth.frames[f], &expected);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      worst = std::max(worst, (solved.world_positions[j] - expected.world_positions[j]).norm());
    }
  }
  return worst;
}

TEST(LiveTracker, RecoversTheWalkFrameByFrame) {
  LiveTrackReport report;
  // Noise-free markers, a weak pull toward the previous pose: converged to well under 0.01 cm.
  EXPECT_LT(WorstJointError(12, {}, &report), 1e-2);
  EXPECT_EQ(report.markers_predicted, 0);
}

TEST(LiveTracker, PredictionBridgesAShortOcclusion) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const std::vector<int> hidden = {skeleton.FindJoint("LeftForeArm"), skeleton.FindJoint("LeftHand")};
  ASSERT_GE(hidden[0], 0);
  ASSERT_GE(hidden[1], 0);
  LiveTrackReport report;
  const double predicted = WorstJointError(12, hidden, &report);
  const double left_out = WorstJointError(0, hidden, &report);
  // The occluded forearm and hand follow their markers' extrapolation instead of staying put.
  EXPECT_LT(predicted, left_out);
}

}  // namespace
}  // namespace mocapsolve
