// A template for a carried joint: the same joint one period away, found from the joints
// the markers still see, and bent to meet both solved edges.
#include "signal/joint_gap_template.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"
#include "signal/joint_gap_carry.h"

namespace mocapsolve {
namespace {

constexpr int kPeriod = 80;

// Thigh, shin and foot swinging with one period, the foot with a second harmonic that no
// cubic across half a period follows.
Motion Periodic(const Skeleton& skeleton, int frames) {
  const int thigh = skeleton.FindJoint("LeftUpLeg"), shin = skeleton.FindJoint("LeftLeg");
  const int foot = skeleton.FindJoint("LeftFoot");
  Motion motion;
  motion.frame_rate = 60.0;
  for (int f = 0; f < frames; ++f) {
    Pose pose = RestPose(skeleton);
    const double phase = 2.0 * M_PI * f / kPeriod;
    pose.rotations[thigh] = ExpMap(Eigen::Vector3d(0.5 * std::sin(phase), 0.1 * std::cos(phase), 0.0));
    pose.rotations[shin] = ExpMap(Eigen::Vector3d(0.6 + 0.6 * std::sin(phase + 1.0), 0.0, 0.0));
    pose.rotations[foot] =
        ExpMap(Eigen::Vector3d(0.3 * std::cos(phase) + 0.25 * std::sin(2.0 * phase), 0.0, 0.2 * std::sin(phase)));
    motion.frames.push_back(pose);
  }
  return motion;
}

double MaxAngle(const Motion& a, const Motion& b, int joint, int first, int last) {
  double worst = 0.0;
  for (int f = first; f <= last; ++f) {
    worst = std::max(worst, a.frames[f].rotations[joint].angularDistance(b.frames[f].rotations[joint]));
  }
  return worst;
}

TEST(JointGapTemplate, AFootHiddenForMostOfAStrideFollowsTheStrideBefore) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int foot = skeleton.FindJoint("LeftFoot");
  const Motion truth = Periodic(skeleton, 300);
  const CarriedJointRun run{foot, 150, 209};  // 60 frames, three quarters of a period.
  std::vector<std::vector<char>> carried(skeleton.num_joints(), std::vector<char>(300, 0));
  for (int f = run.first; f <= run.last; ++f) carried[foot][f] = 1;
  Motion held = truth;
  for (int f = run.first; f <= run.last; ++f) held.frames[f].rotations[foot] = Eigen::Quaterniond::Identity();

  const int tau = FindTemplateShift(skeleton, held, carried, run, JointTemplateOptions());
  ASSERT_NE(tau, 0);
  EXPECT_EQ(std::abs(tau) % kPeriod, 0) << tau;

  Motion hermite = held, templated = held;
  CarryJoints(skeleton, {run}, 2, &hermite);
  const JointTemplateOptions options;
  CarryJoints(skeleton, {run}, 2, &options, &templated);
  // The motion repeats exactly: the template is the truth up to rounding; the cubic misses
  // the second harmonic by a tenth of a radian or more.
  EXPECT_LT(MaxAngle(templated, truth, foot, run.first, run.last), 1e-9);
  EXPECT_GT(MaxAngle(hermite, truth, foot, run.first, run.last), 0.1);
  // Other joints and frames untouched.
  EXPECT_EQ(MaxAngle(templated, held, foot, 0, run.first - 1), 0.0);
  EXPECT_EQ(MaxAngle(templated, held, foot, run.last + 1, 299), 0.0);
}

TEST(JointGapTemplate, SearchesOnlyShiftsWithinTheBound) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int foot = skeleton.FindJoint("LeftFoot");
  const Motion motion = Periodic(skeleton, 300);
  const CarriedJointRun run{foot, 150, 209};
  std::vector<std::vector<char>> carried(skeleton.num_joints(), std::vector<char>(300, 0));
  for (int f = run.first; f <= run.last; ++f) carried[foot][f] = 1;
  JointTemplateOptions options;
  options.max_shift_frames = kPeriod;  // One period away: found.
  const int tau = FindTemplateShift(skeleton, motion, carried, run, options);
  EXPECT_EQ(std::abs(tau), kPeriod);
  options.max_shift_frames = kPeriod / 2;  // Half a period: nothing repeats that near.
  EXPECT_EQ(FindTemplateShift(skeleton, motion, carried, run, options), 0);
}

TEST(JointGapTemplate, NoneWhereTheMotionDoesNotRepeat) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int thigh = skeleton.FindJoint("LeftUpLeg"), foot = skeleton.FindJoint("LeftFoot");
  Motion motion = Periodic(skeleton, 300);
  // The thigh lifts steadily: no other window moves as the one around the gap.
  for (int f = 0; f < 300; ++f) motion.frames[f].rotations[thigh] = ExpMap(Eigen::Vector3d(0.01 * f, 0.0, 0.0));
  const CarriedJointRun run{foot, 150, 209};
  std::vector<std::vector<char>> carried(skeleton.num_joints(), std::vector<char>(300, 0));
  for (int f = run.first; f <= run.last; ++f) carried[foot][f] = 1;
  EXPECT_EQ(FindTemplateShift(skeleton, motion, carried, run, JointTemplateOptions()), 0);
  // A run at the take's end has one solved side: no template either.
  EXPECT_EQ(FindTemplateShift(skeleton, Periodic(skeleton, 300), carried, {foot, 250, 299}, JointTemplateOptions()), 0);
}

// The search with every shift's cost computed in full (no early stop, no bound): the
// shift FindTemplateShift must return, whatever it skips to get there.
int BruteForceShift(const Skeleton& skeleton, const Motion& motion, const std::vector<std::vector<char>>& carried,
                    const CarriedJointRun& run, const JointTemplateOptions& options) {
  const int frames = motion.num_frames(), j = run.joint, a = run.first - 1, b = run.last + 1;
  const int lo = std::max(0, a - options.margin), hi = std::min(frames - 1, b + options.margin);
  double best = options.max_rms_angle * options.max_rms_angle;
  int best_tau = 0;
  for (int tau = -a; tau <= frames - 1 - b; ++tau) {
    if (tau == 0 || std::abs(tau) > options.max_shift_frames) continue;
    bool source_observed = true;
    for (int f = a; f <= b; ++f) source_observed = source_observed && !carried[j][f + tau];
    if (!source_observed) continue;
    double sum = 0.0;
    int counted = 0, possible = 0;
    for (int f = lo; f <= hi; ++f) {
      const int g = f + tau;
      if (g < 0 || g >= frames) {
        possible += skeleton.num_joints();
        continue;
      }
      for (int k = 1; k < skeleton.num_joints(); ++k) {
        if (skeleton.num_rotation_dofs(k) == 0 || (k == j && f > a && f < b)) continue;
        ++possible;
        if (carried[k][f] || carried[k][g]) continue;
        const double angle = motion.frames[f].rotations[k].angularDistance(motion.frames[g].rotations[k]);
        sum += angle * angle;
        ++counted;
      }
    }
    if (counted == 0 || 2 * counted < possible) continue;
    if (sum / counted < best) {
      best = sum / counted;
      best_tau = tau;
    }
  }
  return best_tau;
}

// Many shifts qualify (a loose bound, noise on every joint, other joints carried too), so
// the search's shortcuts (the early stop, the bound without atan2) decide most of them:
// the shift found is the one every cost computed in full gives.
TEST(JointGapTemplate, TheShortcutsFindTheShiftOfTheFullSearch) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int foot = skeleton.FindJoint("LeftFoot"), shin = skeleton.FindJoint("LeftLeg");
  const int frames = 400;
  Motion motion = Periodic(skeleton, frames);
  uint64_t state = 12345;
  const auto noise = [&state]() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5;
  };
  for (int f = 0; f < frames; ++f) {
    for (int k = 1; k < skeleton.num_joints(); ++k) {
      const double size = 0.02 + 0.2 * (f % 37) / 37.0;
      motion.frames[f].rotations[k] =
          motion.frames[f].rotations[k] * ExpMap(size * Eigen::Vector3d(noise(), noise(), noise()));
    }
  }
  std::vector<std::vector<char>> carried(skeleton.num_joints(), std::vector<char>(frames, 0));
  for (int f = 60; f <= 90; ++f) carried[shin][f] = 1;
  int found = 0;
  for (const double max_rms : {0.05, 0.15, 0.4, 1.0, 3.0}) {
    for (const CarriedJointRun& run : {CarriedJointRun{foot, 150, 209}, CarriedJointRun{foot, 30, 45},
                                       CarriedJointRun{shin, 200, 260}, CarriedJointRun{foot, 330, 390}}) {
      for (int f = run.first; f <= run.last; ++f) carried[run.joint][f] = 1;
      JointTemplateOptions options;
      options.max_rms_angle = max_rms;
      options.max_shift_frames = 250;
      const int expected = BruteForceShift(skeleton, motion, carried, run, options);
      EXPECT_EQ(FindTemplateShift(skeleton, motion, carried, run, options), expected)
          << "max_rms " << max_rms << " run " << run.joint << " " << run.first;
      found += expected != 0 ? 1 : 0;
      for (int f = run.first; f <= run.last; ++f) carried[run.joint][f] = 0;
      for (int f = 60; f <= 90; ++f) carried[shin][f] = 1;
    }
  }
  EXPECT_GE(found, 8);  // The case is not trivial: shifts are found.
}

// CarryJoints makes one table for every run: the table holds the samples as they were before
// any run was carried, and the carried ones wrong (as the repair's solve has them there, and
// as each carry then rewrites them). The search must find, run after run, the shift the full
// search finds on the motion as it is then; it fails if the bound reads a carried sample.
TEST(JointGapTemplate, OneTableServesEveryRunWhileTheRunsAreCarried) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int foot = skeleton.FindJoint("LeftFoot"), shin = skeleton.FindJoint("LeftLeg");
  const int thigh = skeleton.FindJoint("LeftUpLeg");
  const int frames = 400;
  Motion motion = Periodic(skeleton, frames);
  const std::vector<CarriedJointRun> runs = {{foot, 150, 209}, {foot, 300, 330}, {shin, 120, 160},
                                             {thigh, 215, 225}, {shin, 240, 250}};
  std::vector<std::vector<char>> carried(skeleton.num_joints(), std::vector<char>(frames, 0));
  for (const CarriedJointRun& run : runs) {
    for (int f = run.first; f <= run.last; ++f) {
      carried[run.joint][f] = 1;
      motion.frames[f].rotations[run.joint] = ExpMap(Eigen::Vector3d(2.5, -1.0, 0.5));  // Far off.
    }
  }
  JointTemplateOptions options;
  options.max_shift_frames = 250;
  const JointTemplateTable table(skeleton, motion, carried, 0, frames - 1);
  int found = 0;
  for (const CarriedJointRun& run : runs) {
    const int expected = BruteForceShift(skeleton, motion, carried, run, options);
    EXPECT_EQ(FindTemplateShift(skeleton, motion, carried, table, run, options), expected) << run.joint;
    found += expected != 0 ? 1 : 0;
    if (expected != 0) CarryFromTemplate(run, expected, &motion);
  }
  EXPECT_GE(found, 3);
}

}  // namespace
}  // namespace mocapsolve
