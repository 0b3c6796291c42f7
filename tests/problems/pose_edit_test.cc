// Eqs. 4-5 (PropagateEdits): exact at the edited frame with w = 1, identity with w = 0,
// continuity through rotations near pi; the spline falloff's shape.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"
#include "problems/edit_propagation/pose_edit.h"
#include "problems/edit_propagation/spline_falloff.h"

namespace mocapsolve {
namespace {

// Angle between two rotations, radians (sign-insensitive).
double Angle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) { return AngularDistance(a, b); }

TEST(UnfoldedLogTest, InvertsExpMapOverTheWholeAngleRange) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  // Angles from 0 through pi (where LogMap folds) to just below 2 pi.
  for (double angle : {0.0, 1e-10, 1e-5, 0.5, 3.0, kPi - 1e-9, kPi, kPi + 1e-9, 4.0, 6.0, 2 * kPi - 1e-4}) {
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::Vector3d axis = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      const Eigen::Vector3d v = angle * axis;
      const Eigen::Quaterniond q = ExpMap(v);
      // 1e-9: atan2 branch near pi and 2 pi; the Taylor branch near 0 is exact to 1e-16.
      EXPECT_LT((UnfoldedLog(q) - v).norm(), 1e-9) << "angle " << angle;
      EXPECT_LT((ExpMap(UnfoldedLog(q)).coeffs() - q.coeffs()).norm(), 1e-12);
    }
  }
}

class PoseEditTest : public ::testing::Test {
 protected:
  void SetUp() override {
    skeleton_ = MakeDemoSkeleton();
    motion_ = MakeDemoWalk(skeleton_, 60, 30.0);
  }
  Skeleton skeleton_;
  Motion motion_;
};

TEST_F(PoseEditTest, FullWeightReproducesTheEditAndZeroWeightLeavesFramesAlone) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> offset(-1.2, 1.2);
  PoseOffsets offsets;
  offsets.frame = 25;
  for (int j = 0; j < skeleton_.num_joints(); j += 2) {
    offsets.rotation_offsets.emplace_back(j, Eigen::Vector3d(offset(rng), offset(rng), offset(rng)));
  }
  offsets.root_translation_offset = Eigen::Vector3d(3.0, -5.0, 1.0);
  PoseEdit edit;
  ASSERT_TRUE(MakeEdit(motion_, offsets, &edit).ok());
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(motion_.num_frames());
  weights[25] = 1.0;
  weights[26] = 0.5;
  Motion out;
  std::vector<EditDeltas> deltas;
  ASSERT_TRUE(PropagateEdits(skeleton_, motion_, {edit}, {weights}, &out, &deltas).ok());
  for (int f = 0; f < motion_.num_frames(); ++f) {
    for (int j = 0; j < skeleton_.num_joints(); ++j) {
      const Eigen::Quaterniond& expected = f == 25 ? edit.edited.rotations[j] : motion_.frames[f].rotations[j];
      if (f == 26) continue;
      // 1e-7 rad: exp(log q) = q to round-off (1e-16 in the coefficients); AngularDistance
      // resolves tiny angles only to ~1e-8.
      EXPECT_LT(Angle(out.frames[f].rotations[j], expected), 1e-7) << "frame " << f << " joint " << j;
      const Eigen::Vector3d& t = f == 25 ? edit.edited.translations[j] : motion_.frames[f].translations[j];
      EXPECT_LT((out.frames[f].translations[j] - t).norm(), 1e-12);
    }
  }
  // Half weight: the log halfway (eq. 5), translation halfway.
  for (int j = 0; j < skeleton_.num_joints(); ++j) {
    const Eigen::Vector3d log_before = UnfoldedLog(motion_.frames[26].rotations[j]);
    // Both sides may differ by the series' sign: compare rotations instead.
    const Eigen::Quaterniond expected = ExpMap(log_before + 0.5 * deltas[0].rotation[j]);
    const Eigen::Quaterniond flipped = ExpMap(UnfoldedLog(Eigen::Quaterniond(-motion_.frames[26].rotations[j].coeffs())) +
                                              0.5 * deltas[0].rotation[j]);
    EXPECT_LT(std::min(Angle(out.frames[26].rotations[j], expected), Angle(out.frames[26].rotations[j], flipped)),
              1e-9) << "joint " << j;
  }
  EXPECT_LT((out.frames[26].translations[0] - motion_.frames[26].translations[0] -
             0.5 * offsets.root_translation_offset).norm(), 1e-12);
  // The delta of an unedited joint is zero, of an edited one not.
  EXPECT_LT(deltas[0].rotation[1].norm(), 1e-12);
  EXPECT_GT(deltas[0].rotation[2].norm(), 1e-3);
}

TEST_F(PoseEditTest, ContinuousThroughRotationsNearPi) {
  // Joint 1's rotation sweeps through pi about a fixed axis over the clip, where LogMap
  // jumps from +pi to -pi; an edit spread with a smooth weight must stay smooth.
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, 1.0, -0.2).normalized();
  const int n = motion_.num_frames();
  for (int f = 0; f < n; ++f) {
    Eigen::Quaterniond q = ExpMap((kPi - 0.3 + 0.6 * f / (n - 1)) * axis);
    if (f % 2 == 1) q.coeffs() = -q.coeffs();  // The source need not be sign-continuous.
    motion_.frames[f].rotations[1] = q;
  }
  PoseOffsets offsets;
  offsets.frame = n / 2;  // Angle exactly pi here.
  offsets.rotation_offsets.emplace_back(1, Eigen::Vector3d(0.0, 0.2, 0.1));
  PoseEdit edit;
  ASSERT_TRUE(MakeEdit(motion_, offsets, &edit).ok());
  const Eigen::VectorXd weights = SplineFalloff(n, offsets.frame, 20.0);
  Motion out;
  ASSERT_TRUE(PropagateEdits(skeleton_, motion_, {edit}, {weights}, &out).ok());
  EXPECT_LT(Angle(out.frames[offsets.frame].rotations[1], edit.edited.rotations[1]), 1e-7);
  for (int f = 1; f < n; ++f) {
    // Source steps are 0.6 / 59 rad; the edit adds at most 0.22 rad * max |w'| (1.5/20).
    EXPECT_LT(Angle(out.frames[f].rotations[1], out.frames[f - 1].rotations[1]), 0.03) << "frame " << f;
  }
  EXPECT_LT(Angle(out.frames[0].rotations[1], motion_.frames[0].rotations[1]), 1e-9);
}

TEST_F(PoseEditTest, SeveralEditsEachExactAtItsFrame) {
  PoseOffsets a, b;
  a.frame = 10;
  a.rotation_offsets.emplace_back(3, Eigen::Vector3d(0.4, 0.0, 0.0));
  b.frame = 40;
  b.rotation_offsets.emplace_back(3, Eigen::Vector3d(0.0, -0.5, 0.2));
  b.root_translation_offset = Eigen::Vector3d(0.0, 2.0, 0.0);
  PoseEdit edit_a, edit_b;
  ASSERT_TRUE(MakeEdit(motion_, a, &edit_a).ok());
  ASSERT_TRUE(MakeEdit(motion_, b, &edit_b).ok());
  // Fields that vanish at the other edit's frame (as the harmonic ones do).
  const int n = motion_.num_frames();
  Eigen::VectorXd wa = SplineFalloff(n, 10, 30.0), wb = SplineFalloff(n, 40, 30.0);
  ASSERT_EQ(wa[40], 0.0);
  ASSERT_EQ(wb[10], 0.0);
  Motion out;
  ASSERT_TRUE(PropagateEdits(skeleton_, motion_, {edit_a, edit_b}, {wa, wb}, &out).ok());
  EXPECT_LT(Angle(out.frames[10].rotations[3], edit_a.edited.rotations[3]), 1e-7);
  EXPECT_LT(Angle(out.frames[40].rotations[3], edit_b.edited.rotations[3]), 1e-7);
  EXPECT_LT((out.frames[40].translations[0] - edit_b.edited.translations[0]).norm(), 1e-12);
  // Frame 25 gets both.
  EXPECT_GT(Angle(out.frames[25].rotations[3], motion_.frames[25].rotations[3]), 0.05);
}

TEST_F(PoseEditTest, BadInputIsAnError) {
  PoseOffsets offsets;
  offsets.frame = 5;
  offsets.rotation_offsets.emplace_back(1, Eigen::Vector3d(0.1, 0, 0));
  PoseEdit edit;
  ASSERT_TRUE(MakeEdit(motion_, offsets, &edit).ok());
  Motion out;
  const Eigen::VectorXd ok = Eigen::VectorXd::Ones(motion_.num_frames());
  EXPECT_FALSE(PropagateEdits(skeleton_, motion_, {edit}, {}, &out).ok());
  EXPECT_FALSE(PropagateEdits(skeleton_, motion_, {edit}, {Eigen::VectorXd::Ones(3)}, &out).ok());
  EXPECT_FALSE(PropagateEdits(skeleton_, motion_, {edit, edit}, {ok, ok}, &out).ok());
  Eigen::VectorXd nan = ok;
  nan[2] = NAN;
  EXPECT_FALSE(PropagateEdits(skeleton_, motion_, {edit}, {nan}, &out).ok());
  offsets.frame = motion_.num_frames();
  EXPECT_FALSE(MakeEdit(motion_, offsets, &edit).ok());
  offsets.frame = 0;
  offsets.rotation_offsets.emplace_back(skeleton_.num_joints(), Eigen::Vector3d::Zero());
  EXPECT_FALSE(MakeEdit(motion_, offsets, &edit).ok());
}

TEST(SplineFalloffTest, CubicBumpOfTheGivenHalfWidth) {
  const Eigen::VectorXd w = SplineFalloff(100, 40, 10.0);
  EXPECT_EQ(w[40], 1.0);
  EXPECT_EQ(w[30], 0.0);
  EXPECT_EQ(w[50], 0.0);
  EXPECT_NEAR(w[45], 0.5, 1e-15);  // h(1/2) = 1/2.
  EXPECT_NEAR(w[35], 0.5, 1e-15);
  EXPECT_NEAR(w[42], 1.0 - 3 * 0.04 + 2 * 0.008, 1e-15);
  for (int f = 41; f < 50; ++f) EXPECT_LT(w[f], w[f - 1]);
  const Eigen::VectorXd region = SplineFalloff(100, 40, 10.0, 38, 43);
  EXPECT_EQ(region[37], 0.0);
  EXPECT_EQ(region[43], 0.0);
  EXPECT_EQ(region[42], w[42]);
}

}  // namespace
}  // namespace mocapsolve
