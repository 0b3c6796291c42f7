// Per-marker solve weights (problems/marker_solve/marker_weights.h): on a synthetic take
// where one marker carries large soft-tissue noise, that marker gets a low weight and the
// others keep 1; with the weight applied, the solve's pose follows the clean markers
// (the joint positions move toward the truth), and the frame solver's three paths agree.
#include "problems/marker_solve/marker_weights.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/sequence_solver.h"
#include "tests/problems/repair_test_support.h"

namespace mocapsolve {
namespace {

constexpr int kNoisy = 4;

// The demo take with every marker jittered by 0.1 cm and marker kNoisy by `sigma` cm
// (smooth in time, as skin sliding over a bone: a random walk, not white noise).
testing::DemoTake NoisyTake(double sigma) {
  testing::DemoTake take = testing::MakeDemoTake(40, 30.0, 5);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector3d slide = Eigen::Vector3d::Zero();
  for (auto& frame : take.clean) {
    for (Eigen::Vector3d& x : frame) x += 0.1 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    slide = 0.7 * slide + 0.7 * sigma * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    frame[kNoisy] += slide;
  }
  return take;
}

MarkerSolveOptions SolveOptions() {
  MarkerSolveOptions options;
  options.prior_rotation_weight = 0.2;
  return options;
}

// Mean joint position error of a solve against the truth, cm.
double JointError(const testing::DemoTake& take, const MarkerSet& markers) {
  Motion motion;
  SequenceSolveReport report;
  EXPECT_TRUE(SolveSequence(take.skeleton, markers, take.clean, SolveOptions(), take.truth.frames[0], &motion, &report).ok());
  FkData fk(take.skeleton), truth(take.skeleton);
  double sum = 0.0;
  int n = 0;
  for (size_t f = 0; f < take.clean.size(); ++f) {
    ForwardKinematics(take.skeleton, motion.frames[f], &fk);
    ForwardKinematics(take.skeleton, take.truth.frames[f], &truth);
    for (int j = 0; j < take.skeleton.num_joints(); ++j, ++n) {
      sum += (fk.world_positions[j] - truth.world_positions[j]).norm();
    }
  }
  return sum / n;
}

TEST(MarkerWeights, ASoftTissueMarkerGetsALowWeightAndThePoseFollowsTheOthers) {
  const testing::DemoTake take = NoisyTake(3.0);
  LearnedMarkerWeights learned;
  MarkerWeightOptions options;
  options.min_weight = 0.01;  // The slide is 40x the others' jitter: let its weight go that low.
  ASSERT_TRUE(LearnMarkerWeights(take.skeleton, take.markers, take.clean, SolveOptions(), options, &learned).ok());
  ASSERT_EQ(static_cast<int>(learned.weight.size()), take.markers.num_markers());
  // The noisy marker's spread is far above the median; every weight is in [min, 1].
  EXPECT_GT(learned.sigma[kNoisy], 5.0 * learned.sigma_ref);
  EXPECT_LT(learned.weight[kNoisy], 0.05);
  EXPECT_GE(learned.weight[kNoisy], options.min_weight);
  // The others' residuals carry some of its error (the solve compromises), but each keeps
  // at least 3x its weight.
  for (int m = 0; m < take.markers.num_markers(); ++m) {
    EXPECT_GE(learned.weight[m], options.min_weight);
    EXPECT_LE(learned.weight[m], 1.0);
    EXPECT_EQ(learned.samples[m], 40);
    if (m != kNoisy) {
      EXPECT_GT(learned.weight[m], 3.0 * learned.weight[kNoisy]) << m;
    }
  }
  MarkerSet weighted;
  ASSERT_TRUE(ApplyMarkerWeights(take.skeleton, take.markers, learned.weight, &weighted).ok());
  EXPECT_EQ(weighted.marker(kNoisy).solve_weight, learned.weight[kNoisy]);
  const double before = JointError(take, take.markers), after = JointError(take, weighted);
  EXPECT_LT(after, 0.8 * before) << "before " << before << " cm, after " << after;
  std::printf("joint error %.3f -> %.3f cm, noisy weight %.3f\n", before, after, learned.weight[kNoisy]);
}

TEST(MarkerWeights, TheFrameSolversAgreeOnAWeightedSet) {
  const testing::DemoTake take = NoisyTake(3.0);
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < take.markers.num_markers(); ++m) specs.push_back(take.markers.marker(m));
  specs[kNoisy].solve_weight = 0.05;
  specs[1].solve_weight = 4.0;
  MarkerSet weighted;
  ASSERT_TRUE(MarkerSet::Create(take.skeleton, specs, &weighted).ok());
  Pose poses[3];
  const SolverKind kinds[3] = {SolverKind::kDls, SolverKind::kDlsGeneric, SolverKind::kCeres};
  for (int k = 0; k < 3; ++k) {
    MarkerSolveOptions options = SolveOptions();
    options.solver = kinds[k];
    options.ceres = DefaultFrameCeresOptions();
    options.ceres.function_tolerance = options.ceres.parameter_tolerance = options.ceres.gradient_tolerance = 1e-14;
    options.dls.max_iterations = 200;
    MarkerFrameSolver solver(take.skeleton, weighted, options);
    poses[k] = take.truth.frames[0];
    FrameSolveReport report;
    ASSERT_TRUE(solver.Solve(take.clean[3], &poses[k], &report).ok());
  }
  FkData a(take.skeleton), b(take.skeleton);
  ForwardKinematics(take.skeleton, poses[0], &a);
  for (int k = 1; k < 3; ++k) {
    ForwardKinematics(take.skeleton, poses[k], &b);
    for (int j = 0; j < take.skeleton.num_joints(); ++j) {
      EXPECT_LT((a.world_positions[j] - b.world_positions[j]).norm(), 1e-4) << "solver " << k << " joint " << j;
    }
  }
  // Bad inputs are errors.
  LearnedMarkerWeights learned;
  MarkerWeightOptions bad;
  bad.min_weight = 0.0;
  EXPECT_FALSE(LearnMarkerWeights(take.skeleton, take.markers, take.clean, SolveOptions(), bad, &learned).ok());
  MarkerSet out;
  EXPECT_FALSE(ApplyMarkerWeights(take.skeleton, take.markers, {1.0}, &out).ok());
}

}  // namespace
}  // namespace mocapsolve
