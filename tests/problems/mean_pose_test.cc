// The mean pose (problems/marker_solve/mean_pose.h): each joint's mean local rotation over a motion.
#include "problems/marker_solve/mean_pose.h"

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

// Rotations about one axis at angles a - d, a, a + d (and their sign-flipped twins): the
// chordal mean is the middle one, whatever the signs the frames store.
TEST(MeanLocalRotation, SymmetricSpreadAboutOneAxisAndSignFlips) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
  const double middle = 2.0, spread = 0.6;
  Motion motion;
  motion.frame_rate = 30.0;
  int k = 0;
  for (double angle : {middle - spread, middle, middle + spread, middle + spread, middle - spread}) {
    Pose pose = RestPose(skeleton);
    Eigen::Quaterniond q(Eigen::AngleAxisd(angle, axis));
    if (k++ % 2 == 1) q.coeffs() = -q.coeffs();  // The same rotation.
    pose.rotations[1] = q;
    motion.frames.push_back(pose);
  }
  const QuaternionVector mean = MeanPose(skeleton, motion);
  ASSERT_EQ(static_cast<int>(mean.size()), skeleton.num_joints());
  // The mean of unit quaternions on one great circle, symmetric about the middle: exact to round-off.
  EXPECT_LT(AngularDistance(mean[1], Eigen::Quaterniond(Eigen::AngleAxisd(middle, axis))), 1e-12);
  EXPECT_LT(AngularDistance(mean[0], Eigen::Quaterniond::Identity()), 1e-12);
  EXPECT_NEAR(mean[1].norm(), 1.0, 1e-15);
  EXPECT_EQ(MeanLocalRotation(Motion(), 0).coeffs(), Eigen::Quaterniond::Identity().coeffs());
}

}  // namespace
}  // namespace mocapsolve
