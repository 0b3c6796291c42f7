// The per-marker residual model's jump detector (marker_residual_model.h) on crafted
// takes: the demo walk (cm) with 0.5 mm of measurement noise, its truth as the reference.
//  - a 2 cm jump of the marker of a bone that marker pins, which the reference follows by
//    turning the joint (the residual steps by 0.6 cm only), is found;
//  - a 1.5 cm jump on a quiet marker, which the reference leans toward by 30-60 % (it steps
//    by 1.05 cm in and out, and is displaced by 0.6 cm between), is found;
//  - a 1 cm jump on a quiet marker, which the reference leans toward by 40 % (the residual
//    steps by 0.6 cm, under the 1 cm floor), is found as a calm plateau;
//  - a 1.2 cm jump under 1 mm of white noise per axis on every marker (the marker's own
//    single-frame step statistic ~7 mm), which the reference leans toward by 20 %, is
//    found by the windowed plateaus, and no other sample;
//  - a calm residual plateau under the floor whose captured samples move smoothly (the
//    reference's joint frame turned) is not found;
//  - a marker noisy all take (5 mm per axis) is not cut away.
#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "problems/marker_repair/marker_residual_model.h"
#include "tests/problems/repair_test_support.h"

namespace mocapsolve {
namespace {

using Observations = std::vector<std::vector<Eigen::Vector3d>>;

constexpr int kFrames = 240;

ResidualModelOptions CmOptions() {  // `repair`'s defaults in cm: 4 cm gates, 1 cm floor.
  ResidualModelOptions options;
  options.min_distance = 1.0;
  options.max_distance = 4.0;
  options.fixed_distance = 4.0;
  return options;
}

Observations Reconstruct(const testing::DemoTake& take, const Motion& motion) {
  Observations out;
  FkData fk(take.skeleton);
  for (const Pose& pose : motion.frames) {
    ForwardKinematics(take.skeleton, pose, &fk);
    out.emplace_back();
    for (int m = 0; m < take.markers.num_markers(); ++m) out.back().push_back(take.markers.Position(m, fk));
  }
  return out;
}

// The clean markers with `sigma` cm of Gaussian noise per axis.
MarkerTrajectories Noisy(const testing::DemoTake& take, const Observations& markers, double sigma, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<std::string> labels;
  for (int m = 0; m < take.markers.num_markers(); ++m) labels.push_back(take.markers.label(m));
  MarkerTrajectories x(labels, static_cast<int>(markers.size()));
  for (size_t f = 0; f < markers.size(); ++f) {
    for (int m = 0; m < take.markers.num_markers(); ++m) {
      x.SetSample(static_cast<int>(f), m, markers[f][m] + Eigen::Vector3d(normal(rng), normal(rng), normal(rng)));
    }
  }
  return x;
}

// The reference leaning toward a displaced marker as the robust tracker does: `joint` of
// frame f turned so that the clean marker's position seen from the joint moves by `lean`.
void TurnJointToward(const testing::DemoTake& take, int joint, int f, int m, const Eigen::Vector3d& lean,
                     Motion* reference) {
  FkData fk(take.skeleton);
  ForwardKinematics(take.skeleton, take.truth.frames[f], &fk);
  const Eigen::Vector3d from = take.clean[f][m] - fk.world_positions[joint];
  const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(from, from + lean);
  const Eigen::Quaterniond& world = fk.world_rotations[joint];
  reference->frames[f].rotations[joint] = take.truth.frames[f].rotations[joint] * (world.conjugate() * turn * world);
}

int CountJumped(const MarkerResidualModel& model, int m, int first, int last) {
  int count = 0;
  for (int f = first; f <= last; ++f) count += model.jumped[f][m] || model.absorbed[f][m];
  return count;
}

// Marker m displaced by `jump` over frames [first, last], the reference's `joint` turned
// toward it by lean(f) of the jump, the samples with `sigma` cm of noise (seed), and the
// residual model of that take.
struct LeaningJump {
  Observations reconstructed;  // X^ of the leaning reference.
  MarkerTrajectories x;        // The captured samples.
  MarkerResidualModel model;
};

LeaningJump MakeLeaningJump(const testing::DemoTake& take, int m, int joint, int first, int last,
                            const Eigen::Vector3d& jump, const std::function<double(int f)>& lean, double sigma,
                            uint32_t seed) {
  Observations observed = take.clean;
  Motion reference = take.truth;
  for (int f = first; f <= last; ++f) {
    observed[f][m] += jump;
    TurnJointToward(take, joint, f, m, lean(f) * jump, &reference);
  }
  LeaningJump out;
  out.reconstructed = Reconstruct(take, reference);
  out.x = Noisy(take, observed, sigma, seed);
  out.model = FitMarkerResidualModel(take.skeleton, take.markers, reference, out.reconstructed, out.x, CmOptions());
  return out;
}

// |step of the residual x - X^ into frame f|.
double ResidualStep(const LeaningJump& take, int m, int f) {
  return ((take.x.position(f, m) - take.reconstructed[f][m]) -
          (take.x.position(f - 1, m) - take.reconstructed[f - 1][m])).norm();
}

TEST(MarkerResidualModel, FindsAJumpTheReferenceAbsorbsByTurningTheJoint) {
  const testing::DemoTake take = testing::MakeDemoTake(kFrames, 120.0, 7);
  const int m = take.markers.FindMarker("Head_0");
  ASSERT_GE(m, 0);
  const int joint = take.markers.marker(m).attachments.front().joint;
  // Frames 100-111: the marker 2 cm off; the reference turns the head so that its model
  // of the marker moves 1.4 cm of the 2 (a one-marker bone: nothing else holds it).
  const int first = 100, last = 111;
  const Eigen::Vector3d jump = 2.0 * Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  const LeaningJump jumped = MakeLeaningJump(take, m, joint, first, last, jump, [](int) { return 0.7; }, 0.05, 1);
  // The residual steps by about 0.6 cm, under the 1 cm floor of the steps.
  EXPECT_LT(ResidualStep(jumped, m, first), 0.8);
  EXPECT_EQ(CountJumped(jumped.model, m, first, last), last - first + 1);
  EXPECT_EQ(CountJumped(jumped.model, m, 0, first - 1) + CountJumped(jumped.model, m, last + 1, kFrames - 1), 0);
}

TEST(MarkerResidualModel, FindsAJumpNearOneCentimetreOnAQuietMarker) {
  const testing::DemoTake take = testing::MakeDemoTake(kFrames, 120.0, 7);
  const int m = take.markers.FindMarker("LeftLeg_2");
  ASSERT_GE(m, 0);
  // Frames 60-75: the marker 1.5 cm off; the reference leans toward it by turning the
  // hip, by 30 % of the jump at its ends and 60 % in its middle (as the robust tracker
  // does), so that seen from its joint or from the joint's parent the marker steps by
  // 1.05 cm in and out but is displaced by 0.6 cm only in between: under the 1 cm floor
  // from the soft-tissue residual.
  const int first = 60, last = 75;
  const Eigen::Vector3d jump = 1.5 * Eigen::Vector3d(-0.6, 0.2, 0.7).normalized();
  const int hip = take.skeleton.parent(take.markers.marker(m).attachments.front().joint);
  const auto lean = [&](int f) { return 0.3 + 0.3 * std::sin(M_PI * (f - first) / (last - first)); };
  const LeaningJump jumped = MakeLeaningJump(take, m, hip, first, last, jump, lean, 0.05, 4);
  EXPECT_GE(CountJumped(jumped.model, m, first, last), last - first);
  EXPECT_EQ(CountJumped(jumped.model, m, 0, first - 1) + CountJumped(jumped.model, m, last + 1, kFrames - 1), 0);
}

TEST(MarkerResidualModel, FindsAOneCentimetreJumpUnderTheFloor) {
  const testing::DemoTake take = testing::MakeDemoTake(kFrames, 120.0, 7);
  const int m = take.markers.FindMarker("LeftLeg_2");
  ASSERT_GE(m, 0);
  // Frames 60-75: the marker 1 cm off; the reference turns the hip toward it by 40 % of
  // the jump: the residual steps by 0.6 cm, under the 1 cm floor of the step pairs.
  const int first = 60, last = 75;
  const Eigen::Vector3d jump = 1.0 * Eigen::Vector3d(0.5, 0.7, -0.4).normalized();
  const int hip = take.skeleton.parent(take.markers.marker(m).attachments.front().joint);
  // 0.2 mm of noise per axis: a quiet marker.
  const LeaningJump jumped = MakeLeaningJump(take, m, hip, first, last, jump, [](int) { return 0.4; }, 0.02, 5);
  EXPECT_LT(ResidualStep(jumped, m, first), 0.8);
  EXPECT_EQ(CountJumped(jumped.model, m, first, last), last - first + 1);
  EXPECT_EQ(CountJumped(jumped.model, m, 0, first - 1) + CountJumped(jumped.model, m, last + 1, kFrames - 1), 0);
}

TEST(MarkerResidualModel, FindsAOnePointTwoCentimetreJumpUnderWhiteNoise) {
  const testing::DemoTake take = testing::MakeDemoTake(kFrames, 120.0, 7);
  const int m = take.markers.FindMarker("LeftLeg_2");
  ASSERT_GE(m, 0);
  // Frames 80-91: the marker 1.2 cm off, the reference's hip turned toward it by 20 %, 1 mm
  // of noise per axis on every sample (a synthetic take made like a capture): the
  // residual steps by about 1 cm, against single steps of noise up to ~7 mm.
  const int first = 80, last = 91;
  const Eigen::Vector3d jump = 1.2 * Eigen::Vector3d(0.4, -0.3, 0.87).normalized();
  const int hip = take.skeleton.parent(take.markers.marker(m).attachments.front().joint);
  const LeaningJump jumped = MakeLeaningJump(take, m, hip, first, last, jump, [](int) { return 0.2; }, 0.1, 8);
  EXPECT_GE(CountJumped(jumped.model, m, first, last), last - first);
  for (int k = 0; k < take.markers.num_markers(); ++k) {
    const int outside = k == m ? CountJumped(jumped.model, k, 0, first - 1) +
                                     CountJumped(jumped.model, k, last + 1, kFrames - 1)
                               : CountJumped(jumped.model, k, 0, kFrames - 1);
    EXPECT_EQ(outside, 0) << take.markers.label(k);
  }
}

TEST(MarkerResidualModel, KeepsAResidualPlateauWhoseSamplesMoveSmoothly) {
  const testing::DemoTake take = testing::MakeDemoTake(kFrames, 120.0, 7);
  const int m = take.markers.FindMarker("LeftToe_1");
  ASSERT_GE(m, 0);
  // Frames 60-75: the reference turns the toe joint by 11 degrees and back, and the joint's
  // markers sit 6 cm from where the marker set puts them (a constant residual, which the
  // turn rotates): each marker's residual, in the joint's frame, steps calmly into a
  // plateau of 0.8 cm and back out. The captured samples move smoothly (nothing jumped),
  // so nothing is found. X^ is the truth's (the residual steps by the turn of the frame).
  const int first = 60, last = 75;
  const int joint = take.markers.marker(m).attachments.front().joint;
  const Eigen::Vector3d offset(0.0, 6.0, 0.0);  // In the joint's frame.
  Observations observed = take.clean;
  FkData fk(take.skeleton);
  for (int f = 0; f < kFrames; ++f) {
    ForwardKinematics(take.skeleton, take.truth.frames[f], &fk);
    for (int k = 0; k < take.markers.num_markers(); ++k) {
      if (take.markers.marker(k).attachments.front().joint != joint) continue;
      observed[f][k] += fk.world_rotations[joint] * offset;
    }
  }
  Motion reference = take.truth;
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.5, 0.7, -0.4).normalized()));
  for (int f = first; f <= last; ++f) {
    reference.frames[f].rotations[joint] = take.truth.frames[f].rotations[joint] * turn;
  }
  const Observations reconstructed = Reconstruct(take, take.truth);
  MarkerTrajectories x = Noisy(take, observed, 0.02, 6);
  const MarkerResidualModel model =
      FitMarkerResidualModel(take.skeleton, take.markers, reference, reconstructed, x, CmOptions());
  FkData turned(take.skeleton);
  ForwardKinematics(take.skeleton, take.truth.frames[first], &fk);
  ForwardKinematics(take.skeleton, reference.frames[first], &turned);
  const double step =  // Of the residual in the joint's frame, R_turned^T R offset - offset.
      (turned.world_rotations[joint].conjugate() * (fk.world_rotations[joint] * offset) - offset).norm();
  EXPECT_GT(step, 0.5);  // Past half the floor: a plateau candidate.
  EXPECT_LT(step, 1.0);  // Under the floor: the step pairs do not see it.
  for (int k = 0; k < take.markers.num_markers(); ++k) {
    EXPECT_EQ(CountJumped(model, k, 0, kFrames - 1), 0) << take.markers.label(k);
  }
}

TEST(MarkerResidualModel, KeepsAMarkerNoisyAllTake) {
  const testing::DemoTake take = testing::MakeDemoTake(kFrames, 120.0, 7);
  const int m = take.markers.FindMarker("LeftForeArm_1");
  ASSERT_GE(m, 0);
  MarkerTrajectories x = Noisy(take, take.clean, 0.05, 2);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 0.5);  // 5 mm per axis, every frame.
  for (int f = 0; f < kFrames; ++f) {
    x.SetSample(f, m, x.position(f, m) + Eigen::Vector3d(normal(rng), normal(rng), normal(rng)));
  }
  const MarkerResidualModel model =
      FitMarkerResidualModel(take.skeleton, take.markers, take.truth, take.clean, x, CmOptions());
  int outlying = 0;
  for (int f = 0; f < kFrames; ++f) outlying += model.Outlying(f, m, x.position(f, m));
  std::printf("noisy marker: %d of %d samples outlying\n", outlying, kFrames);
  EXPECT_LE(outlying, kFrames / 10);
  // The quiet markers keep every sample.
  for (int k = 0; k < take.markers.num_markers(); ++k) {
    if (k == m) continue;
    EXPECT_EQ(CountJumped(model, k, 0, kFrames - 1), 0) << take.markers.label(k);
  }
}

}  // namespace
}  // namespace mocapsolve
