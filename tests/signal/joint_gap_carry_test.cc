// Joints carried across whole-segment gaps: the runs found are those of the joints that
// lost their observing markers, and the carried rotations follow a smooth motion
// across the gap where holding (or a rest pose) does not.
#include "signal/joint_gap_carry.h"

#include <cmath>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

struct Fixture {
  Skeleton skeleton = MakeDemoSkeleton();
  int hips = 0, thigh = 0, shin = 0, foot = 0;
  MarkerSet markers;
  Fixture() {
    thigh = skeleton.FindJoint("LeftUpLeg");
    shin = skeleton.FindJoint("LeftLeg");
    foot = skeleton.FindJoint("LeftFoot");
    std::vector<MarkerSpec> specs = {{"PELV", {{hips, 1.0, {0.0, 5.0, 10.0}}}},
                                     {"LTHI", {{thigh, 1.0, {5.0, -20.0, 3.0}}}},
                                     {"LSHN", {{shin, 1.0, {4.0, -15.0, 3.0}}}},
                                     {"LHEE", {{foot, 1.0, {0.0, -3.0, -6.0}}}},
                                     {"LTOE", {{foot, 1.0, {0.0, -5.0, 12.0}}}}};
    EXPECT_TRUE(MarkerSet::Create(skeleton, specs, &markers).ok());
  }
  // Shin and foot turning smoothly (period 80 frames) about axes of their own.
  Motion Smooth(int frames) const {
    Motion motion;
    motion.frame_rate = 60.0;
    for (int f = 0; f < frames; ++f) {
      Pose pose = RestPose(skeleton);
      const double phase = 2.0 * M_PI * f / 80.0;
      pose.rotations[shin] = ExpMap(Eigen::Vector3d(0.6 * std::sin(phase), 0.0, 0.0));
      pose.rotations[foot] = ExpMap(Eigen::Vector3d(0.2 + 0.3 * std::cos(phase), 0.0, 0.25 * std::sin(phase)));
      motion.frames.push_back(pose);
    }
    return motion;
  }
};

MarkerTrajectories AllPresent(const MarkerSet& markers, int frames) {
  std::vector<std::string> labels;
  for (int m = 0; m < markers.num_markers(); ++m) labels.push_back(markers.label(m));
  MarkerTrajectories x(labels, frames);
  for (int f = 0; f < frames; ++f) {
    for (int m = 0; m < markers.num_markers(); ++m) x.SetSample(f, m, Eigen::Vector3d(f, m, 1.0));
  }
  return x;
}

TEST(JointGapCarry, FindsTheJointsThatLostTheirObservers) {
  const Fixture fx;
  MarkerTrajectories x = AllPresent(fx.markers, 100);
  for (int f = 20; f <= 49; ++f) {
    x.SetMissing(f, fx.markers.FindMarker("LHEE"));
    x.SetMissing(f, fx.markers.FindMarker("LTOE"));
  }
  for (int f = 30; f <= 39; ++f) x.SetMissing(f, fx.markers.FindMarker("LSHN"));
  // One foot marker alone missing elsewhere: the other still observes the foot.
  for (int f = 70; f <= 90; ++f) x.SetMissing(f, fx.markers.FindMarker("LTOE"));
  const std::vector<CarriedJointRun> runs = FindUnobservedJointRuns(fx.skeleton, fx.markers, x);
  // Over 20..49 the shin keeps LSHN only (1 of its 3 observers), the foot none; over
  // 30..39 the thigh keeps LTHI (1 of 4) and the hips PELV and LTHI (2 of 5). While LTOE
  // alone is missing, LHEE is half of the foot's observers: not lost.
  ASSERT_EQ(runs.size(), 4u);
  const int expected[4][3] = {{fx.hips, 30, 39}, {fx.thigh, 30, 39}, {fx.shin, 20, 49}, {fx.foot, 20, 49}};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(runs[i].joint, expected[i][0]) << i;
    EXPECT_EQ(runs[i].first, expected[i][1]) << i;
    EXPECT_EQ(runs[i].last, expected[i][2]) << i;
  }
  // Runs shorter than min_frames are left out.
  EXPECT_EQ(FindUnobservedJointRuns(fx.skeleton, fx.markers, x, 11).size(), 2u);
}

// The demo skeleton with a one-dof knee (about x, as an ASF tibia) whose bone carries a
// knee marker near the axis, a shin marker off it and an ankle marker hidden with the foot;
// the thigh's two markers fix it (and the hips) throughout.
struct HingeFixture {
  Skeleton skeleton;
  int shin = 0, foot = 0;
  MarkerSet markers;
  HingeFixture() {
    const Skeleton demo = MakeDemoSkeleton();
    std::vector<JointSpec> joints;
    for (int j = 0; j < demo.num_joints(); ++j) joints.push_back(demo.joint(j));
    shin = demo.FindJoint("LeftLeg");
    foot = demo.FindJoint("LeftFoot");
    joints[shin].rotation_axes = std::vector<int>{0};
    EXPECT_TRUE(Skeleton::Create(joints, demo.end_sites(), demo.unit(), &skeleton).ok());
    const int thigh = demo.FindJoint("LeftUpLeg");
    std::vector<MarkerSpec> specs = {{"PELV", {{0, 1.0, {0.0, 5.0, 10.0}}}},
                                     {"LTHI", {{thigh, 1.0, {5.0, -20.0, 3.0}}}},
                                     {"LTHF", {{thigh, 1.0, {-3.0, -25.0, 6.0}}}},
                                     {"LKNE", {{shin, 1.0, {5.0, 0.0, 0.5}}}},
                                     {"LSHN", {{shin, 1.0, {4.0, -15.0, 3.0}}}},
                                     {"LANK", {{shin, 1.0, {4.0, -38.0, 0.0}}}},
                                     {"LHEE", {{foot, 1.0, {0.0, -3.0, -6.0}}}},
                                     {"LTOE", {{foot, 1.0, {0.0, -5.0, 12.0}}}}};
    EXPECT_TRUE(MarkerSet::Create(skeleton, specs, &markers).ok());
  }
};

// A hinge whose one angle a marker of its own still fixes is observed, however many of
// its observers (its own, its children's) are gone. Counting markers alone carried a
// walking knee (CMU 02_01, a left foot hidden over frames 204-265: LKNE and LSHN left of
// seven) along the stance poses at its edges, 0.75 rad from the flexion its shin marker
// showed in mid-swing; the re-solve, pulled toward that pose, settled in a second basin
// (the thigh turned 0.1 rad about its axis) and put the foot's markers 250-300 mm off.
TEST(JointGapCarry, AHingeItsOwnMarkerFixesIsNotCarried) {
  const HingeFixture fx;
  MarkerTrajectories x = AllPresent(fx.markers, 100);
  for (const char* label : {"LANK", "LHEE", "LTOE"}) {
    for (int f = 20; f <= 49; ++f) x.SetMissing(f, fx.markers.FindMarker(label));
  }
  // The shin marker gone too over 30..39: the knee marker, 0.5 cm from the axis, does not fix the angle.
  for (int f = 30; f <= 39; ++f) x.SetMissing(f, fx.markers.FindMarker("LSHN"));
  const std::vector<CarriedJointRun> runs = FindUnobservedJointRuns(fx.skeleton, fx.markers, x);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].joint, fx.shin);
  EXPECT_EQ(runs[0].first, 30);
  EXPECT_EQ(runs[0].last, 39);
  EXPECT_EQ(runs[1].joint, fx.foot);
  EXPECT_EQ(runs[1].first, 20);
  EXPECT_EQ(runs[1].last, 49);
}

TEST(JointGapCarry, CarriesRotationsAcrossTheGapWithMatchedVelocities) {
  const Fixture fx;
  const Motion truth = fx.Smooth(100);
  Motion motion = truth;
  const std::vector<CarriedJointRun> runs = {{fx.shin, 30, 39}, {fx.foot, 20, 44}};
  for (const CarriedJointRun& run : runs) {
    for (int f = run.first; f <= run.last; ++f) motion.frames[f].rotations[run.joint] = Eigen::Quaterniond::Identity();
  }
  const Motion held = motion;
  CarryJoints(fx.skeleton, runs, 2, &motion);
  for (const CarriedJointRun& run : runs) {
    double carried = 0.0, rest = 0.0;
    for (int f = run.first; f <= run.last; ++f) {
      const Eigen::Quaterniond& q = truth.frames[f].rotations[run.joint];
      carried = std::max(carried, motion.frames[f].rotations[run.joint].angularDistance(q));
      rest = std::max(rest, held.frames[f].rotations[run.joint].angularDistance(q));
    }
    // A cubic across 12 and 27 frames of an 80-frame period: about a hundredth of a radian
    // (the edge velocities are two-frame differences), against 0.3-0.6 rad at rest.
    EXPECT_LT(carried, 0.03) << run.joint;
    EXPECT_GT(rest, 10.0 * carried) << run.joint;
    // A rotation about one axis stays about that axis.
    if (run.joint == fx.shin) {
      for (int f = run.first; f <= run.last; ++f) {
        const Eigen::Vector3d v = LogMap(motion.frames[f].rotations[run.joint]);
        EXPECT_NEAR(v.y(), 0.0, 1e-12);
        EXPECT_NEAR(v.z(), 0.0, 1e-12);
      }
    }
  }
  // Outside the runs, and other joints, untouched.
  for (int f = 0; f < 100; ++f) {
    for (int j = 0; j < fx.skeleton.num_joints(); ++j) {
      const bool inside = (j == fx.shin && f >= 30 && f <= 39) || (j == fx.foot && f >= 20 && f <= 44);
      if (inside) continue;
      EXPECT_TRUE(motion.frames[f].rotations[j].coeffs() == held.frames[f].rotations[j].coeffs()) << f << " " << j;
    }
  }
}

TEST(JointGapCarry, HoldsTheSolvedSideOfARunAtTheTakesEnd) {
  const Fixture fx;
  Motion motion = fx.Smooth(50);
  CarryJoints(fx.skeleton, {{fx.foot, 40, 49}, {fx.shin, 0, 4}}, 2, &motion);
  for (int f = 40; f <= 49; ++f) {
    EXPECT_TRUE(motion.frames[f].rotations[fx.foot].coeffs() == motion.frames[39].rotations[fx.foot].coeffs());
  }
  for (int f = 0; f <= 4; ++f) {
    EXPECT_TRUE(motion.frames[f].rotations[fx.shin].coeffs() == motion.frames[5].rotations[fx.shin].coeffs());
  }
}

}  // namespace
}  // namespace mocapsolve
