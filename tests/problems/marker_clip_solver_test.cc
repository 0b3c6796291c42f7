#include "problems/marker_solve/marker_clip_solver.h"

#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {
namespace {

// Mean world joint position error against the truth (cm).
double MeanJointError(const Skeleton& skeleton, const Motion& a, const Motion& b) {
  FkData fa(skeleton), fb(skeleton);
  double sum = 0.0;
  for (int f = 0; f < a.num_frames(); ++f) {
    ForwardKinematics(skeleton, a.frames[f], &fa);
    ForwardKinematics(skeleton, b.frames[f], &fb);
    for (int j = 0; j < skeleton.num_joints(); ++j) sum += (fa.world_positions[j] - fb.world_positions[j]).norm();
  }
  return sum / (a.num_frames() * skeleton.num_joints());
}

class MarkerClipSolverTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 rng(1);
    markers_ = MakeSyntheticMarkerSet(skeleton_, 3, rng());
    truth_ = MakeDemoWalk(skeleton_, 60, 60.0);
    FkData fk(skeleton_);
    for (const Pose& pose : truth_.frames) {
      ForwardKinematics(skeleton_, pose, &fk);
      clean_.emplace_back();
      for (int m = 0; m < markers_.num_markers(); ++m) clean_.back().push_back(markers_.Position(m, fk));
    }
  }
  Skeleton skeleton_ = MakeDemoSkeleton();
  MarkerSet markers_;
  Motion truth_;
  std::vector<std::vector<Eigen::Vector3d>> clean_;
};

TEST_F(MarkerClipSolverTest, NoiseFreeFromRestConverges) {
  Motion motion = truth_;
  for (Pose& pose : motion.frames) {
    pose = RestPose(skeleton_);
    pose.translations[0] = truth_.frames[0].translations[0];
  }
  ClipSolveOptions options;
  options.ceres = DefaultClipCeresOptions();
  options.rotation_smoothness = 1e-4;  // Nearly pure data term.
  options.translation_smoothness = 1e-4;
  ClipSolveReport report;
  const Status status = SolveClip(skeleton_, markers_, clean_, options, &motion, &report);
  ASSERT_TRUE(status.ok()) << status.message() << "\n" << report.full;
  // The tiny smoothness weight biases by far less than 0.01 cm.
  EXPECT_LT(MeanJointError(skeleton_, motion, truth_), 1e-2) << report.brief;
  EXPECT_LT(report.rms_marker_error, 1e-2);
}

TEST_F(MarkerClipSolverTest, SmoothnessBeatsPerFrameOnNoisyMarkers) {
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 0.5);  // 5 mm
  auto noisy = clean_;
  for (auto& frame : noisy) {
    for (auto& x : frame) x += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  }
  // Per-frame solutions: the clip's initial guess and the baseline.
  MarkerSolveOptions frame_options;
  frame_options.solver = SolverKind::kDls;
  MarkerFrameSolver frame_solver(skeleton_, markers_, frame_options);
  Motion per_frame = truth_;
  Pose pose = truth_.frames[0];
  for (int f = 0; f < truth_.num_frames(); ++f) {
    FrameSolveReport report;
    ASSERT_TRUE(frame_solver.Solve(noisy[f], &pose, &report).ok());
    per_frame.frames[f] = pose;
  }
  Motion clip = per_frame;
  ClipSolveOptions options;
  options.ceres = DefaultClipCeresOptions();
  options.rotation_smoothness = 30.0;
  options.translation_smoothness = 1.0;
  ClipSolveReport report;
  ASSERT_TRUE(SolveClip(skeleton_, markers_, noisy, options, &clip, &report).ok()) << report.brief;
  const double frame_error = MeanJointError(skeleton_, per_frame, truth_);
  const double clip_error = MeanJointError(skeleton_, clip, truth_);
  EXPECT_LT(clip_error, 0.8 * frame_error) << "per-frame " << frame_error << " cm, clip " << clip_error << " cm";
}

}  // namespace
}  // namespace mocapsolve
