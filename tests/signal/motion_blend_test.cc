// Blending (eq. 6 and section 3): a motion with itself, the weight function, the second
// motion inside the first, and the velocity jump of a real transition (131_01 -> 131_02).
#include "signal/motion_blend.h"

#include <algorithm>
#include <cstdio>

#include <gtest/gtest.h>

#include "io/motion_file.h"
#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

double MaxPoseError(const Motion& a, const Motion& b, int first, int last) {
  double worst = 0.0;
  for (int f = first; f <= last; ++f) {
    for (size_t j = 0; j < a.frames[f].rotations.size(); ++j) {
      worst = std::max(worst, AngularDistance(a.frames[f].rotations[j], b.frames[f].rotations[j]));
      worst = std::max(worst, (a.frames[f].translations[j] - b.frames[f].translations[j]).norm());
    }
  }
  return worst;
}

TEST(MotionBlend, WeightsEaseInAndOut) {
  BlendOptions options;
  options.b_offset = 10;
  options.transition_start = 20;
  options.transition_end = 30;
  std::vector<double> w = BlendWeights(100, 200, options);
  ASSERT_EQ(w.size(), 210u);
  EXPECT_EQ(w[19], 0.0);
  EXPECT_EQ(w[20], 0.0);
  EXPECT_NEAR(w[25], 0.5, 1e-12);
  EXPECT_EQ(w[30], 1.0);
  EXPECT_EQ(w[209], 1.0);
  // Inside: B (frames 10..59) eases out over its last 10 frames and A takes over again.
  w = BlendWeights(100, 50, options);
  ASSERT_EQ(w.size(), 100u);
  EXPECT_EQ(w[40], 1.0);
  EXPECT_NEAR(w[54], 0.5, 1e-12);
  EXPECT_EQ(w[59], 0.0);
  EXPECT_EQ(w[70], 0.0);
}

TEST(MotionBlend, BlendingAMotionWithItselfGivesTheMotion) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = MakeDemoWalk(skeleton, 150, 60.0);
  for (BlendMethod method : {BlendMethod::kMultiresolution, BlendMethod::kWeightedSum}) {
    BlendOptions options;
    options.transition_start = 40;
    options.transition_end = 60;
    options.method = method;
    Motion out;
    ASSERT_TRUE(BlendMotions(motion, motion, options, &out).ok());
    ASSERT_EQ(out.num_frames(), 150);
    EXPECT_LT(MaxPoseError(motion, out, 0, 149), 1e-9);
  }
}

TEST(MotionBlend, SecondMotionInsideTheFirst) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion a = MakeDemoWalk(skeleton, 200, 60.0);
  Motion b = MakeDemoWalk(skeleton, 60, 60.0);
  for (Pose& pose : b.frames) pose.translations[0].y() += 20.0;  // A crouch-free hop.
  BlendOptions options;
  options.b_offset = 50;
  options.transition_start = 50;
  options.transition_end = 60;
  options.method = BlendMethod::kWeightedSum;
  Motion out;
  ASSERT_TRUE(BlendMotions(a, b, options, &out).ok());
  ASSERT_EQ(out.num_frames(), 200);
  EXPECT_LT(MaxPoseError(a, out, 0, 50), 1e-9);
  EXPECT_LT(MaxPoseError(a, out, 109, 199), 1e-9);
  EXPECT_NEAR(out.frames[80].translations[0].y(), b.frames[30].translations[0].y(), 1e-9);
  options.method = BlendMethod::kMultiresolution;
  options.pyramid.levels = 3;
  ASSERT_TRUE(BlendMotions(a, b, options, &out).ok());
  // Far from the seams the blend is A (resp. B) again; near them it is smoothed.
  EXPECT_LT(MaxPoseError(a, out, 0, 20), 1e-6);
  EXPECT_LT(MaxPoseError(a, out, 150, 199), 1e-6);
  EXPECT_NEAR(out.frames[80].translations[0].y(), b.frames[30].translations[0].y(), 1e-6);
}

TEST(MotionBlend, BadWindowsAreErrors) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion a = MakeDemoWalk(skeleton, 100, 60.0);
  Motion out;
  BlendOptions options;
  options.transition_start = 50;
  options.transition_end = 50;
  EXPECT_FALSE(BlendMotions(a, a, options, &out).ok());
  options.transition_end = 120;
  EXPECT_FALSE(BlendMotions(a, a, options, &out).ok());
  options.transition_end = 60;
  options.b_offset = 55;
  EXPECT_FALSE(BlendMotions(a, a, options, &out).ok());
}

// 131_01 into 131_02 (same skeleton): the largest jump of any joint's velocity between
// consecutive frames around the transition, against the largest in either input.
TEST(MotionBlend, RealTransitionHasNoVelocityJump) {
  MOCAPSOLVE_DATA_FILE(path_a, "bvh/131_01.bvh");
  MOCAPSOLVE_DATA_FILE(path_b, "bvh/131_02.bvh");
  Skeleton skeleton_a, skeleton_b;
  Motion a, b;
  ASSERT_TRUE(ReadMotionFile(path_a, MotionFileOptions(), &skeleton_a, &a).ok());
  ASSERT_TRUE(ReadMotionFile(path_b, MotionFileOptions(), &skeleton_b, &b).ok());
  ASSERT_EQ(skeleton_a.num_joints(), skeleton_b.num_joints());
  auto max_of = [](const std::vector<double>& v, int first, int last) {
    double m = 0.0;
    for (int i = std::max(first, 0); i <= std::min<int>(last, v.size() - 1); ++i) {
      m = std::max(m, v[i]);
    }
    return m;
  };
  const double jump_a = max_of(VelocityJumps(skeleton_a, a), 0, a.num_frames());
  const double jump_b = max_of(VelocityJumps(skeleton_b, b), 0, b.num_frames());
  BlendOptions options;
  options.b_offset = 400;
  options.transition_start = 400;
  options.transition_end = 412;  // 0.1 s at 120 Hz.
  options.pyramid.levels = 5;
  double jump[2];
  for (int k = 0; k < 2; ++k) {
    options.method = k == 0 ? BlendMethod::kMultiresolution : BlendMethod::kWeightedSum;
    Motion out;
    ASSERT_TRUE(BlendMotions(a, b, options, &out).ok());
    jump[k] = max_of(VelocityJumps(skeleton_a, out), 400 - 64, 412 + 64);
  }
  std::printf("131_01 -> 131_02 at frames 400:412, largest velocity jump (units/frame): "
              "multires %.4g, weighted %.4g; inputs %.4g and %.4g\n",
              jump[0], jump[1], jump_a, jump_b);
  EXPECT_LE(jump[0], std::max(jump_a, jump_b));
  EXPECT_GT(jump[1], std::max(jump_a, jump_b));
}

}  // namespace
}  // namespace mocapsolve
