// CompactMotion (kinematics/compact_motion.h): float storage within its stated bounds,
// fixed translations exact, a quarter of the memory.
#include "kinematics/compact_motion.h"

#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"

namespace mocapsolve {
namespace {

// The demo skeleton walking about 10 m from the origin with random rotations.
Motion RandomMotion(const Skeleton& skeleton, int frames) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  Motion motion;
  motion.frame_rate = 120.0;
  for (int f = 0; f < frames; ++f) {
    Pose pose = RestPose(skeleton);
    pose.translations[0] = Eigen::Vector3d(1000.0 + 3.0 * f, 90.0 + n(rng), -700.0 + n(rng));  // cm.
    for (Eigen::Quaterniond& q : pose.rotations) q = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    motion.frames.push_back(pose);
  }
  return motion;
}

TEST(CompactMotion, WithinFloatPrecisionAndFixedTranslationsExact) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = RandomMotion(skeleton, 50);
  const CompactMotion compact(motion);
  ASSERT_EQ(compact.num_frames(), 50);
  ASSERT_EQ(compact.num_joints(), skeleton.num_joints());
  EXPECT_EQ(compact.frame_rate(), 120.0);
  const Motion back = compact.ToMotion();
  FkData a(skeleton), b(skeleton);
  double worst_position = 0.0;
  for (int f = 0; f < motion.num_frames(); ++f) {
    for (int j = 1; j < skeleton.num_joints(); ++j) {
      // Not animated: the rest offset, bit for bit.
      EXPECT_EQ(back.frames[f].translations[j], motion.frames[f].translations[j]);
    }
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      EXPECT_NEAR(std::abs(back.frames[f].rotations[j].norm() - 1.0), 0.0, 1e-15);
      EXPECT_LT(back.frames[f].rotations[j].angularDistance(motion.frames[f].rotations[j]), 2e-7);
    }
    ForwardKinematics(skeleton, motion.frames[f], &a);
    ForwardKinematics(skeleton, back.frames[f], &b);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      worst_position = std::max(worst_position, (a.world_positions[j] - b.world_positions[j]).norm());
    }
  }
  // 12 m from the origin in cm: 2^-24 x 1,200 cm = 7e-5 cm for the root, plus the
  // rotations' rounding along the chain: far inside 0.001 cm (0.01 mm).
  EXPECT_LT(worst_position, 2e-4);
  EXPECT_GT(worst_position, 0.0);  // Float, not double: the test can tell.
  // One joint at a time, as the writers read it.
  EXPECT_EQ(compact.Rotation(7, 3).coeffs(), back.frames[7].rotations[3].coeffs());
  EXPECT_EQ(compact.Translation(7, 0), back.frames[7].translations[0]);
  // 16 B per rotation and 12 B for the root per frame.
  EXPECT_LE(compact.bytes(), 50u * (skeleton.num_joints() * 16 + 12) + skeleton.num_joints() * 28 + 64);
}

TEST(CompactMotion, Empty) {
  const CompactMotion none{Motion()};
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.ToMotion().num_frames(), 0);
}

}  // namespace
// A take assembled window by window (pipeline/take_windows.h) holds what the whole motion
// built at once holds, also when a joint fixed in the first part moves in a later one.
TEST(CompactMotion, AppendedPartsEqualTheWholeMotion) {
  const Skeleton skeleton = MakeDemoSkeleton();
  Motion motion = RandomMotion(skeleton, 30);
  for (int f = 20; f < 30; ++f) motion.frames[f].translations[3] += Eigen::Vector3d(0.5, 0.0, 0.25 * f);
  const CompactMotion whole(motion);
  CompactMotion parts;
  parts.Reserve(30);
  parts.Append(motion, 0, 12);
  parts.Append(motion, 12, 0);
  parts.Append(motion, 12, 8);
  parts.Append(motion, 20, 10);
  ASSERT_EQ(parts.num_frames(), 30);
  ASSERT_EQ(parts.num_joints(), skeleton.num_joints());
  EXPECT_EQ(parts.frame_rate(), 120.0);
  for (int f = 0; f < 30; ++f) {
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      EXPECT_EQ(parts.Rotation(f, j).coeffs(), whole.Rotation(f, j).coeffs()) << f << " " << j;
      EXPECT_EQ(parts.Translation(f, j), whole.Translation(f, j)) << f << " " << j;
    }
  }
}

}  // namespace mocapsolve
