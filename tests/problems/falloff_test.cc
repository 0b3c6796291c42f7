// The magic-wand falloff (problems/edit_propagation/falloff.h): eq. 3's full sum against a
// direct pseudo-inverse of L, dense against sparse kernels, the weight contract of all
// three methods, bad input, pose features, and the periodic-walk criterion on CMU 16_15.
#include "problems/edit_propagation/falloff.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/SVD>
#include <gtest/gtest.h>

#include "io/motion_file.h"
#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"
#include "problems/edit_propagation/falloff_analysis.h"
#include "problems/edit_propagation/pose_features.h"
#include "problems/edit_propagation/pose_kernel.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// The demo walk with seeded rotation noise (so no two poses coincide and the Laplacian's
// eigenvalues are simple).
Motion NoisyWalk(const Skeleton& skeleton, int frames, double fps, unsigned seed) {
  Motion motion = MakeDemoWalk(skeleton, frames, fps);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (Pose& pose : motion.frames) {
    for (auto& q : pose.rotations) q = (q * ExpMap(Eigen::Vector3d(noise(rng), noise(rng), noise(rng)))).normalized();
  }
  return motion;
}

Eigen::MatrixXd WalkFeatures(int frames, unsigned seed) {
  const Skeleton skeleton = MakeDemoSkeleton();
  Eigen::MatrixXd features;
  EXPECT_TRUE(PoseFeatures(skeleton, NoisyWalk(skeleton, frames, 30.0, seed), PoseFeatureOptions(), &features).ok());
  return features;
}

TEST(GreenFunction, FullSumIsThePseudoInverseOfL) {
  const Eigen::MatrixXd features = WalkFeatures(50, 1);
  FalloffOptions options;
  options.eigenpairs = 0;
  options.kernel = KernelMode::kDense;
  GreenFunction green;
  ASSERT_TRUE(green.Build(features, options).ok());
  EXPECT_EQ(green.eigenpairs_used(), 49);  // Every term but lambda_0.
  EXPECT_GT(green.sigma_used(), 0.0);

  // L from eq. 1-2 directly, its pseudo-inverse by SVD.
  const Eigen::MatrixXd k = DensePoseKernel(features, green.sigma_used());
  const Eigen::VectorXd s = k.rowwise().sum().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd l = Eigen::MatrixXd::Identity(50, 50) - s.asDiagonal() * k * s.asDiagonal();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(l, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::VectorXd inverse = svd.singularValues();
  for (int i = 0; i < inverse.size(); ++i) inverse[i] = inverse[i] > 1e-9 ? 1.0 / inverse[i] : 0.0;
  const Eigen::MatrixXd pinv = svd.matrixV() * inverse.asDiagonal() * svd.matrixU().transpose();
  // The projector identity: L G = I - phi_0 phi_0^T, phi_0 = D^1/2 1 / |D^1/2 1|.
  const Eigen::VectorXd phi0 = k.rowwise().sum().cwiseSqrt().normalized();
  const Eigen::MatrixXd projector = Eigen::MatrixXd::Identity(50, 50) - phi0 * phi0.transpose();
  Eigen::MatrixXd g(50, 50);
  for (int i = 0; i < 50; ++i) {
    Eigen::VectorXd row;
    green.Row(i, &row);
    g.row(i) = row.transpose();
  }
  const double scale = pinv.cwiseAbs().maxCoeff();
  // Both are O(cond(L)) * 1e-16 from exact; cond(L restricted) is ~1e3 here.
  EXPECT_LT((g - pinv).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_LT((l * g - projector).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((g - g.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale);
}

TEST(GreenFunction, DenseAndSparseAgreeWhenKnnCoversEverything) {
  const Eigen::MatrixXd features = WalkFeatures(40, 2);
  // With knn = n - 1 the kNN kernel is the dense kernel.
  const double sigma = 4.0 * MedianStepDistance(features);
  const Eigen::MatrixXd dense_kernel = DensePoseKernel(features, sigma);
  const Eigen::MatrixXd sparse_kernel = SparsePoseKernel(PoseNeighbourGraph(features, 39), sigma);
  EXPECT_LT((dense_kernel - sparse_kernel).cwiseAbs().maxCoeff(), 1e-12);

  FalloffOptions options;
  options.eigenpairs = 8;
  options.knn = 39;
  options.kernel = KernelMode::kDense;
  GreenFunction dense, sparse;
  ASSERT_TRUE(dense.Build(features, options).ok());
  options.kernel = KernelMode::kSparse;
  ASSERT_TRUE(sparse.Build(features, options).ok());
  EXPECT_FALSE(dense.sparse_used());
  EXPECT_TRUE(sparse.sparse_used());
  EXPECT_EQ(sparse.eigenpairs_used(), 8);
  for (int i = 0; i < 40; i += 7) {
    Eigen::VectorXd a, b;
    dense.Row(i, &a);
    sparse.Row(i, &b);
    // Lanczos tolerance 1e-10 on eigenvalues; G's terms scale with 1/lambda.
    EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-6 * a.cwiseAbs().maxCoeff()) << "row " << i;
  }
}

TEST(Falloff, WeightContractForEveryMethod) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = NoisyWalk(skeleton, 80, 30.0, 3);
  for (FalloffMethod method : {FalloffMethod::kGreen, FalloffMethod::kDiffusion, FalloffMethod::kIsomap}) {
    SCOPED_TRACE(FalloffMethodName(method));
    FalloffOptions options;
    options.region_begin = 10;
    options.region_end = 70;
    Falloff f;
    ASSERT_TRUE(ComputeFalloff(skeleton, motion, 25, method, options, &f).ok());
    ASSERT_EQ(f.weight.size(), 80);
    EXPECT_EQ(f.weight[25], 1.0);
    EXPECT_EQ(f.distance[25], 0.0);
    EXPECT_GE(f.weight.minCoeff(), 0.0);
    EXPECT_LE(f.weight.maxCoeff(), 1.0);
    EXPECT_LT((f.distance + f.weight - Eigen::VectorXd::Ones(80)).cwiseAbs().maxCoeff(), 1e-15);
    for (int j = 0; j < 80; ++j) {
      if (j < 10 || j >= 70) {
        EXPECT_EQ(f.weight[j], 0.0) << j;
      }
    }
    // The least similar frame of the region has weight 0.
    int least = 10;
    for (int j = 10; j < 70; ++j) {
      const bool further = method == FalloffMethod::kGreen ? f.raw[j] < f.raw[least] : f.raw[j] > f.raw[least];
      if (further) least = j;
    }
    EXPECT_EQ(f.weight[least], 0.0) << "frame " << least;
    // Not trivially 0/1: some frame of the region is in between.
    EXPECT_GT(((f.weight.array() > 0.05) && (f.weight.array() < 0.95)).count(), 0);
  }
}

TEST(Falloff, GreenFunctionRowsMatchComputeFalloff) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = NoisyWalk(skeleton, 60, 30.0, 4);
  Eigen::MatrixXd features;
  ASSERT_TRUE(PoseFeatures(skeleton, motion, PoseFeatureOptions(), &features).ok());
  GreenFunction green;
  ASSERT_TRUE(green.Build(features, FalloffOptions()).ok());
  Falloff once, reused;
  ASSERT_TRUE(ComputeFalloff(skeleton, motion, 17, FalloffMethod::kGreen, FalloffOptions(), &once).ok());
  green.Weights(17, 0, 60, &reused);
  EXPECT_LT((once.weight - reused.weight).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(once.eigenpairs_used, 10);
  EXPECT_EQ(once.sigma_used, green.sigma_used());

  // Several edits at once: the same falloffs as one at a time, for every method.
  for (FalloffMethod method : {FalloffMethod::kGreen, FalloffMethod::kDiffusion, FalloffMethod::kIsomap}) {
    std::vector<Falloff> many;
    ASSERT_TRUE(ComputeFalloffs(skeleton, motion, {3, 17, 40}, method, FalloffOptions(), &many).ok());
    ASSERT_EQ(many.size(), 3u);
    for (int e = 0; e < 3; ++e) {
      Falloff single;
      ASSERT_TRUE(ComputeFalloff(skeleton, motion, std::vector<int>{3, 17, 40}[e], method, FalloffOptions(), &single).ok());
      EXPECT_LT((many[e].weight - single.weight).cwiseAbs().maxCoeff(), 1e-12) << FalloffMethodName(method) << e;
    }
  }
  std::vector<Falloff> many;
  EXPECT_FALSE(ComputeFalloffs(skeleton, motion, {3, 60}, FalloffMethod::kGreen, FalloffOptions(), &many).ok());
}

TEST(Falloff, RejectsBadInput) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = NoisyWalk(skeleton, 30, 30.0, 5);
  Falloff f;
  FalloffOptions options;
  Status status = ComputeFalloff(skeleton, motion, 30, FalloffMethod::kGreen, options, &f);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("frame"), std::string::npos) << status.message();
  options.region_begin = 10;
  options.region_end = 20;
  status = ComputeFalloff(skeleton, motion, 5, FalloffMethod::kGreen, options, &f);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("outside the region"), std::string::npos) << status.message();
  options = FalloffOptions();
  options.kernel = KernelMode::kSparse;
  options.eigenpairs = 0;
  status = ComputeFalloff(skeleton, motion, 5, FalloffMethod::kGreen, options, &f);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("eigenpairs"), std::string::npos) << status.message();
  options = FalloffOptions();
  options.sigma = -1.0;
  EXPECT_FALSE(ComputeFalloff(skeleton, motion, 5, FalloffMethod::kIsomap, options, &f).ok());
  Motion still = motion;
  for (Pose& pose : still.frames) pose = still.frames[0];
  status = ComputeFalloff(skeleton, still, 5, FalloffMethod::kGreen, FalloffOptions(), &f);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("sigma"), std::string::npos) << status.message();
  Motion two = motion;
  two.frames.resize(2);
  EXPECT_FALSE(ComputeFalloff(skeleton, two, 0, FalloffMethod::kGreen, FalloffOptions(), &f).ok());
}

TEST(PoseFeatures, LayoutWeightsTemporalTermAndErrors) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = NoisyWalk(skeleton, 20, 30.0, 6);
  PoseFeatureOptions options;
  options.joints = {"LeftUpLeg", "RightLeg"};
  options.joint_weights = {2.0, 0.5};
  options.temporal_weight = 3.0;
  Eigen::MatrixXd f;
  ASSERT_TRUE(PoseFeatures(skeleton, motion, options, &f).ok());
  ASSERT_EQ(f.rows(), 20);
  ASSERT_EQ(f.cols(), 7);
  const int left = skeleton.FindJoint("LeftUpLeg"), right = skeleton.FindJoint("RightLeg");
  for (int i = 0; i < 20; ++i) {
    EXPECT_LT((f.block<1, 3>(i, 0).transpose() - 2.0 * LogMap(motion.frames[i].rotations[left])).norm(), 1e-12);
    EXPECT_LT((f.block<1, 3>(i, 3).transpose() - 0.5 * LogMap(motion.frames[i].rotations[right])).norm(), 1e-12);
    EXPECT_NEAR(f(i, 6), 3.0 * i / 30.0, 1e-12);
  }
  options.joint_weights = {1.0};
  EXPECT_FALSE(PoseFeatures(skeleton, motion, options, &f).ok());
  options.joints = {"Tail"};
  options.joint_weights.clear();
  Status status = PoseFeatures(skeleton, motion, options, &f);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("Tail"), std::string::npos);
  EXPECT_FALSE(PoseFeatures(skeleton, Motion(), PoseFeatureOptions(), &f).ok());
}

TEST(PoseFeatures, ContinuousThroughHalfTurn) {
  // One joint turning steadily about z from 0 to 1.5 pi: the log-quaternion grows steadily
  // (sign-continuous series, no hemisphere flip at pi).
  const Skeleton skeleton = MakeDemoSkeleton();
  Motion motion = MakeDemoWalk(skeleton, 31, 30.0);
  const int j = skeleton.FindJoint("Head");
  for (int i = 0; i <= 30; ++i) {
    motion.frames[i].rotations[j] = Eigen::Quaterniond(Eigen::AngleAxisd(1.5 * kPi * i / 30.0, Eigen::Vector3d::UnitZ()));
  }
  PoseFeatureOptions options;
  options.joints = {"Head"};
  Eigen::MatrixXd f;
  ASSERT_TRUE(PoseFeatures(skeleton, motion, options, &f).ok());
  for (int i = 0; i <= 30; ++i) EXPECT_NEAR(f(i, 2), 1.5 * kPi * i / 30.0, 1e-9) << i;
}

TEST(FalloffAnalysis, PeriodKinkAndEnds) {
  // The demo walk's cycle is 1.1 s: 33 frames at 30 fps.
  EXPECT_NEAR(DetectPosePeriod(WalkFeatures(150, 7)), 33, 1);
  Eigen::MatrixXd line(100, 1);
  for (int i = 0; i < 100; ++i) line(i, 0) = i;
  EXPECT_EQ(DetectPosePeriod(line), 0);

  Eigen::VectorXd parabola(11), corner(11);
  for (int i = 0; i < 11; ++i) parabola[i] = 1.0 - 0.01 * (i - 5) * (i - 5), corner[i] = 1.0 - 0.1 * std::abs(i - 5);
  EXPECT_NEAR(KinkRatio(parabola, 5), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(KinkRatio(corner, 5), 2.0, 1e-12);
  EXPECT_NEAR(SecondDifference(parabola, 5), -0.02, 1e-15);
  EXPECT_TRUE(std::isnan(SecondDifference(parabola, 0)));
  EXPECT_EQ(FalloffEnd(corner, 5, +1, 0.75), 8);
  EXPECT_EQ(FalloffEnd(corner, 5, -1, 0.75), 2);
  EXPECT_EQ(FalloffEnd(corner, 5, -1, 0.1), -1);
}

// A glitch island (one joint flipped by 180 degrees for 4 frames, as CMU 131_01's thumb)
// is nearly its own graph component; its tiny eigenvalue must not swamp eq. 3's sum.
TEST(Falloff, GlitchIslandDoesNotSwampTheSum) {
  const Skeleton skeleton = MakeDemoSkeleton();
  Motion motion = NoisyWalk(skeleton, 120, 30.0, 8);
  const int j = skeleton.FindJoint("LeftForeArm");
  ASSERT_GE(j, 0);
  for (int i = 70; i < 74; ++i) {
    motion.frames[i].rotations[j] = motion.frames[i].rotations[j] * Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0);
  }
  FalloffOptions options;
  options.region_end = 66;  // Normalize away from the island.
  Falloff robust, swamped;
  ASSERT_TRUE(ComputeFalloff(skeleton, motion, 20, FalloffMethod::kGreen, options, &robust).ok());
  options.null_eigenvalue = 0.0;
  ASSERT_TRUE(ComputeFalloff(skeleton, motion, 20, FalloffMethod::kGreen, options, &swamped).ok());
  // Half a demo cycle (16 frames) from the edit: the opposite phase.
  EXPECT_LT(robust.weight[36], 0.3);
  EXPECT_LT(robust.weight[4], 0.3);
  EXPECT_GT(robust.weight[53], 0.7);  // The same phase, one cycle (33 frames) later.
  // Without the threshold the island's indicator term flattens the falloff: the control.
  EXPECT_GT(swamped.weight[36], robust.weight[36] + 0.3);
}

// The kNN search runs in the leading principal subspace and reranks; on a real clip
// (93-D pose vectors) it must find nearly all of the exact nearest neighbours.
TEST(PoseNeighbourGraph, ApproximateSearchFindsTheNearestPoses) {
  MOCAPSOLVE_DATA_FILE(path, "bvh/16_15.bvh");
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadMotionFile(path, MotionFileOptions(), &skeleton, &motion).ok());
  Eigen::MatrixXd features;
  ASSERT_TRUE(PoseFeatures(skeleton, motion, PoseFeatureOptions(), &features).ok());
  ASSERT_GT(features.cols(), 12);  // So the projected search is the one exercised.
  const int n = static_cast<int>(features.rows()), knn = 10;
  const auto graph = PoseNeighbourGraph(features, knn);
  int found = 0;
  for (int i = 0; i < n; ++i) {
    std::vector<std::pair<double, int>> exact;
    for (int j = 0; j < n; ++j) {
      if (j != i) exact.emplace_back((features.row(i) - features.row(j)).squaredNorm(), j);
    }
    std::partial_sort(exact.begin(), exact.begin() + knn, exact.end());
    for (int r = 0; r < knn; ++r) {
      for (const GraphEdge& e : graph[i]) found += e.neighbour == exact[r].second;
    }
    // Symmetric, sorted, no self, lengths are the pose distances.
    for (size_t r = 0; r < graph[i].size(); ++r) {
      const GraphEdge& e = graph[i][r];
      ASSERT_NE(e.neighbour, i);
      if (r > 0) {
        ASSERT_LT(graph[i][r - 1].neighbour, e.neighbour);
      }
      EXPECT_NEAR(e.distance, (features.row(i) - features.row(e.neighbour)).norm(), 1e-12);
      bool back = false;
      for (const GraphEdge& f : graph[e.neighbour]) back = back || f.neighbour == i;
      ASSERT_TRUE(back) << i << " -> " << e.neighbour;
    }
  }
  const double recall = static_cast<double>(found) / (n * knn);
  EXPECT_GT(recall, 0.95) << recall;
  RecordProperty("recall", std::to_string(recall));
}

// The criterion on a real periodic walk: an edit reaches the same phase of the
// other cycles (weight >= 0.8) and leaves the opposite phase (<= 0.2).
TEST(Falloff, Walk1615ReachesSamePhaseOfOtherStrides) {
  MOCAPSOLVE_DATA_FILE(path, "bvh/16_15.bvh");
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadMotionFile(path, MotionFileOptions(), &skeleton, &motion).ok());
  Eigen::MatrixXd features;
  ASSERT_TRUE(PoseFeatures(skeleton, motion, PoseFeatureOptions(), &features).ok());
  const int period = DetectPosePeriod(features);
  EXPECT_GT(period, 100);  // A gait cycle at 120 fps: about 1.2 s.
  EXPECT_LT(period, 180);
  for (KernelMode mode : {KernelMode::kDense, KernelMode::kSparse}) {
    FalloffOptions options;
    options.kernel = mode;
    GreenFunction green;
    ASSERT_TRUE(green.Build(features, options).ok());
    for (int frame : {100, 200, 300}) {
      SCOPED_TRACE("frame " + std::to_string(frame) + (mode == KernelMode::kDense ? " dense" : " sparse"));
      Falloff f;
      green.Weights(frame, 0, motion.num_frames(), &f);
      const PhaseFrames phases = FindPhaseFrames(features, frame, period);
      ASSERT_GE(phases.same.size(), 2u);
      ASSERT_GE(phases.opposite.size(), 2u);
      for (int j : phases.same) EXPECT_GE(f.weight[j], 0.8) << "same phase frame " << j;
      for (int j : phases.opposite) EXPECT_LE(f.weight[j], 0.2) << "opposite phase frame " << j;
    }
  }
}

}  // namespace
}  // namespace mocapsolve
