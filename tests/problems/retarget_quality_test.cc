// MeasureRetargetQuality on the demo skeleton (synthetic): the limb directions after one
// constant rotation (a turned result is no error; a bent forearm is, on that limb only),
// penetration under the floor, the own-skeleton joint error, coverage per body part; and
// the quality gate's retarget checks on those figures.
#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "pipeline/quality_gate.h"
#include "problems/retarget/joint_map.h"
#include "problems/retarget/retarget_quality.h"
#include "problems/retarget/synthetic_skinned_character.h"
#include "problems/retarget/vertex_subsampling.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

class RetargetQualityTest : public ::testing::Test {
 protected:
  void SetUp() override {
    skeleton_ = MakeDemoSkeleton();
    motion_ = MakeDemoWalk(skeleton_, 60, 30.0);
    ASSERT_TRUE(BuildJointMap(skeleton_, skeleton_, {}, &map_).ok());
    ASSERT_TRUE(map_.target_roles.humanoid);
  }
  RetargetQuality Measure(const Motion& result, const RetargetSetup* setup = nullptr, bool own = false) {
    RetargetQualityInputs in;
    in.source = &skeleton_;
    in.source_motion = &motion_;
    in.target = &skeleton_;
    in.result = &result;
    in.joint_map = &map_;
    in.setup = setup;
    in.target_mesh = setup != nullptr ? &mesh_ : nullptr;
    in.own_skeleton = own;
    return MeasureRetargetQuality(in);
  }
  const LimbDirectionError& Limb(const RetargetQuality& q, const std::string& name) {
    for (const LimbDirectionError& l : q.limbs) {
      if (l.limb == name) return l;
    }
    ADD_FAILURE() << name;
    return q.limbs.front();
  }
  Skeleton skeleton_;
  Motion motion_;
  JointMap map_;
  SkinnedMesh mesh_;
};

TEST_F(RetargetQualityTest, ATurnedResultHasNoLimbErrorButItsAlignmentAngle) {
  const RetargetQuality same = Measure(motion_);
  ASSERT_EQ(same.limbs.size(), 8u);
  EXPECT_NEAR(same.limb_mean_deg, 0.0, 1e-4);  // acos near 1: ~1e-6 rad of rounding.
  EXPECT_NEAR(same.alignment_deg, 0.0, 1e-4);
  Motion turned = motion_;
  const Eigen::Quaterniond yaw(Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()));
  for (Pose& pose : turned.frames) {
    pose.rotations[0] = yaw * pose.rotations[0];
    pose.translations[0] = yaw * pose.translations[0];
  }
  const RetargetQuality q = Measure(turned);
  EXPECT_NEAR(q.limb_mean_deg, 0.0, 1e-4);
  EXPECT_NEAR(q.limb_p95_deg, 0.0, 1e-4);
  EXPECT_NEAR(q.alignment_deg, 30.0, 1e-6);
}

TEST_F(RetargetQualityTest, ABentForearmIsAnErrorOnThatLimbOnly) {
  Motion bent = motion_;
  const int forearm = skeleton_.FindJoint("LeftForeArm");
  const Eigen::Quaterniond bend(Eigen::AngleAxisd(20.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  for (Pose& pose : bent.frames) pose.rotations[forearm] = pose.rotations[forearm] * bend;
  const RetargetQuality q = Measure(bent);
  // The common rotation leans toward the bent limb (1 of 8): 16.8 degrees measured.
  EXPECT_NEAR(Limb(q, "left_forearm").mean_deg, 20.0, 4.0);
  EXPECT_LT(Limb(q, "left_upper_arm").mean_deg, 3.0);
  EXPECT_LT(Limb(q, "right_shin").mean_deg, 3.0);
  EXPECT_GT(q.limb_p95_deg, 15.0);
}

TEST_F(RetargetQualityTest, PenetrationBelowTheRestClearance) {
  motion_ = Motion();
  motion_.frame_rate = 30.0;
  motion_.frames.assign(4, RestPose(skeleton_));
  Motion lowered = motion_;
  lowered.frames[2].translations[0].y() -= 5.0;  // cm (the demo skeleton's unit).
  const RetargetQuality q = Measure(lowered);
  // The toes' rest height (1 cm) is the rest floor's: 5 cm lower puts them 4 cm under y = 0.
  EXPECT_NEAR(q.penetration_cm, 4.0, 1e-9);
  EXPECT_NEAR(q.penetration_frame_share, 0.25, 1e-12);
  EXPECT_NEAR(Measure(motion_).penetration_cm, 0.0, 1e-9);
}

TEST_F(RetargetQualityTest, OwnSkeletonJointError) {
  EXPECT_TRUE(std::isnan(Measure(motion_).self_joint_error_max_cm));  // Not the own skeleton: not measured.
  EXPECT_NEAR(Measure(motion_, nullptr, true).self_joint_error_max_cm, 0.0, 1e-9);
  Motion shifted = motion_;
  for (Pose& pose : shifted.frames) pose.translations[0].x() += 2.0;
  const RetargetQuality q = Measure(shifted, nullptr, true);
  EXPECT_NEAR(q.self_joint_error_mean_cm, 2.0, 1e-9);
  EXPECT_NEAR(q.self_joint_error_max_cm, 2.0, 1e-9);
}

TEST_F(RetargetQualityTest, CoverageCountsTrackedVerticesPerBodyPartAndTheGateFailsAnUntrackedLimb) {
  mesh_ = MakeCylinderCharacter(skeleton_);
  RetargetSetup hands_only, everywhere;
  const int left_hand = skeleton_.FindJoint("LeftHand"), right_hand = skeleton_.FindJoint("RightHand");
  for (int v = 0; v < mesh_.num_vertices(); ++v) {
    TrackedVertex t;
    t.source_vertex = t.target_vertex = v;
    everywhere.tracked.push_back(t);
    const int j = DominantJoint(mesh_, v);
    if (j == left_hand || j == right_hand) hands_only.tracked.push_back(t);
  }
  const RetargetQuality bad = Measure(motion_, &hands_only);
  EXPECT_EQ(bad.min_limb_vertices, 0);
  // A forearm's direction ends at its hand: the hand's vertices place it, so a forearm
  // without mesh of its own (RobotExpressive's) is covered; bare upper arms are not.
  const int left_forearm = skeleton_.FindJoint("LeftForeArm"), right_forearm = skeleton_.FindJoint("RightForeArm");
  RetargetSetup bare_forearms;
  for (const TrackedVertex& t : everywhere.tracked) {
    const int j = DominantJoint(mesh_, t.target_vertex);
    if (j != left_forearm && j != right_forearm) bare_forearms.tracked.push_back(t);
  }
  EXPECT_GT(Measure(motion_, &bare_forearms).min_limb_vertices, 3);
  const RetargetQuality good = Measure(motion_, &everywhere);
  EXPECT_GT(good.min_limb_vertices, 3);
  int total = 0;
  for (const auto& [part, count] : good.coverage) total += count;
  EXPECT_EQ(total, mesh_.num_vertices());

  QualityGate gate;
  gate.max_penetration_cm = 0.0;  // The demo walk's toes dip under their rest height.
  QualityVerdict verdict;
  CheckRetargetQuality(gate, bad, "Robot", &verdict);
  EXPECT_FALSE(verdict.pass);
  ASSERT_EQ(verdict.failures.size(), 1u);
  EXPECT_THAT(verdict.failures[0], HasSubstr("Robot: "));
  EXPECT_THAT(verdict.failures[0], HasSubstr("tracked by 0 vertices < 3"));
  verdict = QualityVerdict();
  CheckRetargetQuality(gate, good, "Figure", &verdict);
  EXPECT_TRUE(verdict.pass);
}

TEST(RetargetQualityGate, EachThresholdAndNaNNotChecked) {
  RetargetQuality q;
  q.limb_mean_deg = 22.0;
  q.limb_p95_deg = 45.0;
  q.foot_skate_cm_s = 1.5;
  q.penetration_cm = 2.0;
  q.self_joint_error_max_cm = std::nan("");  // Not the own skeleton.
  QualityVerdict verdict;
  CheckRetargetQuality(QualityGate(), q, "X", &verdict);
  EXPECT_FALSE(verdict.pass);
  ASSERT_EQ(verdict.failures.size(), 4u);
  EXPECT_EQ(verdict.failures[0], "X: limb direction error (mean) 22 deg > 20 deg");
  EXPECT_THAT(verdict.failures[3], HasSubstr("ground penetration 2 cm > 1 cm"));
  QualityGate off;
  off.max_limb_mean_deg = off.max_limb_p95_deg = off.max_foot_skate_cm_s = off.max_penetration_cm = 0.0;
  verdict = QualityVerdict();
  CheckRetargetQuality(off, q, "X", &verdict);
  EXPECT_TRUE(verdict.pass);
}

}  // namespace
}  // namespace mocapsolve
