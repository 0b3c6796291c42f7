// PelvisRestCorrection (problems/retarget/pelvis_rest_correction.h): the full rotation where
// the two rigs' pelvis children are one set turned, a turn about up where their designs
// differ or where two (mirror) children cannot tell a tilt from a design.
#include "problems/retarget/pelvis_rest_correction.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

double AngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return Eigen::AngleAxisd((a.conjugate() * b).normalized()).angle() * 180.0 / M_PI;
}

// A CMU-like pelvis: thighs down and out, the spine straight up.
std::vector<Eigen::Vector3d> Children() {
  return {Eigen::Vector3d(0.6, -0.75, 0.1).normalized(), Eigen::Vector3d(-0.6, -0.75, 0.1).normalized(),
          Eigen::Vector3d(0.0, 1.0, -0.05).normalized()};
}

std::vector<Eigen::Vector3d> Turned(const Eigen::Quaterniond& r, const std::vector<Eigen::Vector3d>& u) {
  std::vector<Eigen::Vector3d> v;
  for (const Eigen::Vector3d& x : u) v.push_back(r * x);
  return v;
}

TEST(PelvisRestCorrectionTest, SameChildrenTurnedGiveTheFullRotation) {
  // The same rig whose rest pose is tilted and turned against its bind pose.
  const Eigen::Quaterniond r = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitY());
  const PelvisCorrection c = PelvisRestCorrection(Children(), Turned(r, Children()));
  EXPECT_LT(c.residual_deg, 1e-6);
  EXPECT_EQ(c.tilt_kept, 1.0);
  EXPECT_LT(AngleDeg(c.rotation, r), 1e-6);
}

TEST(PelvisRestCorrectionTest, ChildrenLeaningByDesignOnlyTurnAboutUp) {
  // RobotExpressive-like: thighs out and slightly up, the spine 40 degrees back; facing +90.
  const std::vector<Eigen::Vector3d> design = {Eigen::Vector3d(0.95, 0.15, -0.28).normalized(),
                                               Eigen::Vector3d(-0.95, 0.14, -0.27).normalized(),
                                               Eigen::Vector3d(0.0, 0.77, -0.64).normalized()};
  const Eigen::Quaterniond facing(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
  const PelvisCorrection c = PelvisRestCorrection(Children(), Turned(facing, design));
  EXPECT_GT(c.residual_deg, kPelvisDisagreeDeg);
  EXPECT_EQ(c.tilt_kept, 0.0);
  EXPECT_LT(AngleDeg(c.rotation, facing), 5.0);  // The facing, no tilt (Kabsch's is 21 degrees off).
  EXPECT_GT(AngleDeg(BestRestRotation(Children(), Turned(facing, design)), facing), 15.0);
  const Eigen::Vector3d up = c.rotation * Eigen::Vector3d::UnitY();
  EXPECT_NEAR(up.y(), 1.0, 1e-12);
}

TEST(PelvisRestCorrectionTest, TwoMirrorChildrenNeverTilt) {
  // Two thighs fit any tilt about the axis between them exactly: no evidence for it.
  const std::vector<Eigen::Vector3d> u = {Children()[0], Children()[1]};
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitX()));
  const PelvisCorrection c = PelvisRestCorrection(u, Turned(tilt, u));
  EXPECT_LT(c.residual_deg, 1e-6);
  EXPECT_EQ(c.tilt_kept, 0.0);
  EXPECT_LT(AngleDeg(c.rotation, Eigen::Quaterniond::Identity()), 1e-6);
}

TEST(PelvisRestCorrectionTest, NoChildrenIsTheIdentity) {
  const PelvisCorrection c = PelvisRestCorrection({}, {});
  EXPECT_LT(AngleDeg(c.rotation, Eigen::Quaterniond::Identity()), 1e-12);
}

}  // namespace
}  // namespace mocapsolve
