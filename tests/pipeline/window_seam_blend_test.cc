// WindowSeamBlend (pipeline/window_seam_blend.h): two windows whose motions differ by a
// constant angle over the frames both solve are joined without a jump at the seam; frames
// away from the seam are their own window's; a channel both windows agree on stays exact;
// with no blend the cores join edge to edge.
#include "pipeline/window_seam_blend.h"

#include <cmath>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// One window's motion of two joints over frames [w.first, w.last]: joint 0 turns about z
// at 0.01 rad per frame plus `offset`; joint 1 is fixed (its translation a bone offset).
Motion WindowMotion(const FrameWindow& w, double offset) {
  Motion motion;
  motion.frame_rate = 120.0;
  for (int f = w.first; f <= w.last; ++f) {
    Pose pose;
    pose.rotations = {Eigen::Quaterniond(Eigen::AngleAxisd(0.01 * f + offset, Eigen::Vector3d::UnitZ())),
                      Eigen::Quaterniond::Identity()};
    pose.translations = {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.0, 0.437, 0.0)};
    motion.frames.push_back(pose);
  }
  return motion;
}

double Angle(const Pose& pose) { return 2.0 * std::atan2(pose.rotations[0].z(), pose.rotations[0].w()); }

Motion Join(int blend_frames, const FrameWindow& a, const FrameWindow& b) {
  WindowSeamBlend seams(blend_frames);
  Motion joined;
  joined.frame_rate = 120.0;
  const WindowSeamBlend::Emit emit = [&](const Motion& m, int first, int count) {
    joined.frames.insert(joined.frames.end(), m.frames.begin() + first, m.frames.begin() + first + count);
    return Status::Ok();
  };
  EXPECT_TRUE(seams.Add(WindowMotion(a, 0.0), a, false, emit).ok());
  EXPECT_TRUE(seams.Add(WindowMotion(b, 0.2), b, true, emit).ok());
  return joined;
}

const FrameWindow kFirst{0, 159, 0, 99};     // first, last, core_first, core_last.
const FrameWindow kSecond{40, 199, 100, 199};

TEST(WindowSeamBlend, JoinsTwoWindowsWithoutAJump) {
  const Motion joined = Join(20, kFirst, kSecond);
  ASSERT_EQ(joined.num_frames(), 200);
  double largest_step = 0.0;
  for (int f = 1; f < 200; ++f) {
    largest_step = std::max(largest_step, std::abs(Angle(joined.frames[f]) - Angle(joined.frames[f - 1])));
  }
  // The motion's own step is 0.01 rad; the 0.2 rad difference spread over 40 frames adds
  // about 0.2 * pi / 2 / 39 = 0.008 at the ease's steepest (edge to edge: 0.21 in a frame).
  EXPECT_LT(largest_step, 0.019);
  for (int f = 0; f < 80; ++f) EXPECT_NEAR(Angle(joined.frames[f]), 0.01 * f, 1e-12) << f;
  for (int f = 120; f < 200; ++f) EXPECT_NEAR(Angle(joined.frames[f]), 0.01 * f + 0.2, 1e-12) << f;
  for (const Pose& pose : joined.frames) {  // What both windows agree on, exactly.
    EXPECT_EQ(pose.translations[1], Eigen::Vector3d(0.0, 0.437, 0.0));
    EXPECT_EQ(pose.translations[0], Eigen::Vector3d(0.1, 0.2, 0.3));
    EXPECT_EQ(pose.rotations[1].coeffs(), Eigen::Quaterniond::Identity().coeffs());
  }
}

TEST(WindowSeamBlend, WithoutABlendTheCoresJoinEdgeToEdge) {
  const Motion joined = Join(0, kFirst, kSecond);
  ASSERT_EQ(joined.num_frames(), 200);
  EXPECT_NEAR(Angle(joined.frames[99]), 0.99, 1e-12);
  EXPECT_NEAR(Angle(joined.frames[100]), 1.0 + 0.2, 1e-12);
}

// The blend is bounded by the frames the windows share: a second window with 10 frames
// of context before its core blends over 10 frames each side, not 20.
TEST(WindowSeamBlend, BlendsOnlyOverFramesBothWindowsSolved) {
  const FrameWindow narrow{90, 199, 100, 199};
  const Motion joined = Join(20, kFirst, narrow);
  ASSERT_EQ(joined.num_frames(), 200);
  for (int f = 0; f < 90; ++f) EXPECT_NEAR(Angle(joined.frames[f]), 0.01 * f, 1e-12) << f;
  for (int f = 110; f < 200; ++f) EXPECT_NEAR(Angle(joined.frames[f]), 0.01 * f + 0.2, 1e-12) << f;
  EXPECT_GT(Angle(joined.frames[100]) - 1.0, 0.01);  // Between the two.
  EXPECT_LT(Angle(joined.frames[100]) - 1.0, 0.19);
}

}  // namespace
}  // namespace mocapsolve
