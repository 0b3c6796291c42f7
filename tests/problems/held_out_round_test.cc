// The held-out score of a fit's round (problems/marker_solve/held_out_round.h): on a
// synthetic take it is the markers' noise for the model that made them and grows when a
// bone's length is off (what a round trading a length against marker offsets does, which
// its fitted RMS hides); and the kept round is the latest within the tolerance of the lowest.
#include "problems/marker_solve/held_out_round.h"

#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

struct NoisyTake {
  Skeleton skeleton;  // cm
  MarkerSet markers;
  Motion motion;
  std::vector<std::vector<Eigen::Vector3d>> observed;
};

NoisyTake MakeNoisyTake(double noise_cm) {
  NoisyTake t;
  t.skeleton = MakeDemoSkeleton();
  t.markers = MakeSyntheticMarkerSet(t.skeleton, 3, 5);
  t.motion = MakeDemoWalk(t.skeleton, 60, 30.0);
  std::mt19937 rng(3);
  std::normal_distribution<double> gauss(0.0, noise_cm);
  FkData fk(t.skeleton);
  for (const Pose& pose : t.motion.frames) {
    ForwardKinematics(t.skeleton, pose, &fk);
    t.observed.emplace_back();
    for (int m = 0; m < t.markers.num_markers(); ++m) {
      t.observed.back().push_back(t.markers.Position(m, fk) + Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)));
    }
  }
  return t;
}

MarkerSolveOptions Solve() {
  MarkerSolveOptions solve;
  solve.solver = SolverKind::kDls;
  return solve;
}

TEST(HeldOutRound, TheTakesOwnModelScoresAtItsNoiseAndAWrongLengthScoresWorse) {
  const NoisyTake t = MakeNoisyTake(0.2);
  HeldOutRoundOptions options;
  options.max_frames = 20;  // Every 3rd frame.
  double truth = 0.0;
  Status status = HeldOutRoundScore(t.skeleton, t.markers, t.motion, t.observed, Solve(), options, &truth);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_GT(truth, 0.0);
  EXPECT_LT(truth, 1.5);  // cm: the noise (0.2 cm per axis) and the others' pose error.
  // Every thigh 25 % longer, the markers as they were: each leg marker is placed by the
  // others through a wrong knee.
  std::vector<JointSpec> joints;
  for (int j = 0; j < t.skeleton.num_joints(); ++j) {
    joints.push_back(t.skeleton.joint(j));
    if (t.skeleton.name(j).find("Leg") != std::string::npos) joints.back().offset *= 1.25;
  }
  Skeleton longer;
  ASSERT_TRUE(Skeleton::Create(joints, t.skeleton.end_sites(), t.skeleton.unit(), &longer).ok());
  double wrong = 0.0;
  status = HeldOutRoundScore(longer, t.markers, t.motion, t.observed, Solve(), options, &wrong);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_GT(wrong, 1.5 * truth);
  // The score does not depend on the threads.
  options.num_threads = 1;
  double one_thread = 0.0;
  ASSERT_TRUE(HeldOutRoundScore(t.skeleton, t.markers, t.motion, t.observed, Solve(), options, &one_thread).ok());
  EXPECT_EQ(one_thread, truth);
}

TEST(HeldOutRound, KeptRoundIsTheLatestWithinTheToleranceOfTheLowest) {
  EXPECT_EQ(KeptRound({}, 0.05), -1);
  EXPECT_EQ(KeptRound({10.0, 9.0, 9.4, 12.0}, 0.05), 2);  // 9.4 <= 1.05 * 9.0.
  EXPECT_EQ(KeptRound({10.0, 9.0, 9.6}, 0.05), 1);        // 9.6 > 9.45: clearly worse.
  EXPECT_EQ(KeptRound({10.0, 9.0, 9.6}, 0.0), 1);
  EXPECT_EQ(KeptRound({5.0, 5.0}, 0.0), 1);               // A tie keeps the later round.
}

TEST(HeldOutRound, MotionOfOtherFramesIsAnError) {
  NoisyTake t = MakeNoisyTake(0.2);
  t.motion.frames.pop_back();
  double score = 0.0;
  EXPECT_FALSE(HeldOutRoundScore(t.skeleton, t.markers, t.motion, t.observed, Solve(), HeldOutRoundOptions(), &score).ok());
}

}  // namespace
}  // namespace mocapsolve
