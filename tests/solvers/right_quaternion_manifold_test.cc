#include "solvers/right_quaternion_manifold.h"

#include <algorithm>
#include <random>

#include <ceres/manifold_test_utils.h>
#include <gtest/gtest.h>

#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

TEST(RightQuaternionManifold, InvariantsHold) {
  using namespace ceres;  // The macro names Ceres' matchers unqualified.
  RightQuaternionManifold manifold;
  std::mt19937 rng(4);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
    q.normalize();
    Eigen::Vector4d x = q.coeffs();
    // Include a rotation by almost pi, where log changes branch.
    if (trial == 0) x = ExpMap(Eigen::Vector3d(kPi - 1e-6, 0, 0)).coeffs();
    Eigen::Vector3d delta(normal(rng), normal(rng), normal(rng));
    delta *= 0.5;
    Eigen::Quaterniond qy(normal(rng), normal(rng), normal(rng), normal(rng));
    const Eigen::Vector4d y = qy.normalized().coeffs();
    // Numeric derivatives inside the macro use h ~ 1e-8 relative: 1e-6 is their limit.
    EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-6);
  }
}

TEST(RightQuaternionManifold, PlusMultipliesOnTheRight) {
  RightQuaternionManifold manifold;
  const Eigen::Quaterniond q = ExpMap(Eigen::Vector3d(0.3, -0.2, 1.0));
  const Eigen::Vector3d delta(0.1, 0.2, -0.3);
  Eigen::Quaterniond out;
  manifold.Plus(q.coeffs().data(), delta.data(), out.coeffs().data());
  EXPECT_LT(AngularDistance(out, q * ExpMap(delta)), 1e-15);
  EXPECT_GT(AngularDistance(out, ExpMap(delta) * q), 1e-3);
}

TEST(RightQuaternionManifold, AmbientFromTangentInvertsPlusJacobian) {
  const Eigen::Quaterniond q = ExpMap(Eigen::Vector3d(0.7, 0.1, -2.0));
  const Eigen::Matrix3d identity = AmbientFromTangent(q.coeffs().data()) * QuaternionPlusJacobian(q.coeffs().data());
  EXPECT_LT((identity - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  // And it ignores the radial direction (changes of |q|).
  EXPECT_LT((AmbientFromTangent(q.coeffs().data()) * q.coeffs()).norm(), 1e-15);
}

}  // namespace
}  // namespace mocapsolve

namespace mocapsolve {
namespace {

TEST(DofQuaternionManifold, InvariantsHoldOnItsSet) {
  using namespace ceres;  // The macro names Ceres' matchers unqualified.
  const std::vector<std::vector<int>> axis_lists = {{0}, {1}, {2}, {0, 2}, {2, 0}, {1, 0}, {2, 1}};
  for (const auto& axes : axis_lists) {
    DofQuaternionManifold manifold(axes);
    const int k = manifold.TangentSize();
    Eigen::VectorXd delta(k);
    for (int i = 0; i < k; ++i) delta[i] = 0.1 * (i + 1);
    for (const double second : {-1.1}) {
      double x_angles[2] = {0.4, second}, y_angles[2] = {-2.0, 0.7};
      Eigen::Vector4d x, y;
      manifold.Compose(x_angles, x.data());
      manifold.Compose(y_angles, y.data());
      EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-6);
    }
  }
}

// On the set, PlusJacobianOnSet equals PlusJacobian (which projects first); off it, it
// declines.
TEST(DofQuaternionManifold, PlusJacobianOnSetMatchesOnTheSet) {
  const std::vector<std::vector<int>> axis_lists = {{0}, {1}, {2}, {0, 1}, {1, 0}, {0, 2}, {2, 0}, {1, 2}, {2, 1}};
  for (const auto& axes : axis_lists) {
    DofQuaternionManifold manifold(axes);
    const int k = manifold.TangentSize();
    for (double t : {0.0, 0.4, -2.9, 3.1}) {
      const double angles[2] = {t, 0.3 * (0.7 - t)};  // Some with w < 0; |t1| < pi/2.
      Eigen::Vector4d q;
      manifold.Compose(angles, q.data());
      double expected[8], got[8];
      manifold.PlusJacobian(q.data(), expected);
      ASSERT_TRUE(manifold.PlusJacobianOnSet(q.data(), got)) << axes.size() << " axes, t " << t;
      for (int i = 0; i < 4 * k; ++i) EXPECT_NEAR(got[i], expected[i], 1e-15);  // Round-off.
    }
    const Eigen::Vector4d off = Eigen::Quaterniond(ExpMap(Eigen::Vector3d(0.3, 0.2, 0.1))).coeffs();
    double unused[8];
    EXPECT_FALSE(manifold.PlusJacobianOnSet(off.data(), unused));
    if (k == 2) {  // Second angle beyond pi/2: the same columns as PlusJacobian's.
      for (const double t0 : {0.2, -2.5, 3.0}) {
        for (const double t1 : {2.0, -1.7, 3.1, -3.0}) {
          const double far[2] = {t0, t1};
          Eigen::Vector4d q;
          manifold.Compose(far, q.data());
          double expected[8], got[8];
          manifold.PlusJacobian(q.data(), expected);
          ASSERT_TRUE(manifold.PlusJacobianOnSet(q.data(), got));
          for (int i = 0; i < 4 * k; ++i) EXPECT_NEAR(got[i], expected[i], 1e-14);
        }
      }
    }
  }
}

// Every point of a two-axis set, the second angle up to a full half turn either way, is
// its own projection: Plus(q, 0) = +-q, small steps stay small, and PlusJacobian is
// Plus's derivative (central differences). (With an
// Euler decomposition alone, a second angle past pi/2 was read as another point of the
// set: Plus(q, 0) was a different rotation, every step from there was rejected, and a
// per-frame solve that crossed pi/2 froze for the frames after it.)
TEST(DofQuaternionManifold, EveryPointOfTheSetIsItsOwnProjection) {
  const std::vector<std::vector<int>> axis_lists = {{0, 1}, {1, 0}, {0, 2}, {2, 0}, {1, 2}, {2, 1}};
  for (const auto& axes : axis_lists) {
    DofQuaternionManifold manifold(axes);
    for (double t0 = -3.1; t0 < 3.2; t0 += 0.31) {
      for (double t1 = -3.1; t1 < 3.2; t1 += 0.29) {
        const double angles[2] = {t0, t1};
        Eigen::Vector4d q, same, moved;
        manifold.Compose(angles, q.data());
        const double zero[2] = {0.0, 0.0}, small[2] = {1e-3, -1e-3};
        manifold.Plus(q.data(), zero, same.data());
        EXPECT_LT(std::min((same - q).norm(), (same + q).norm()), 1e-14) << t0 << " " << t1;
        manifold.Plus(q.data(), small, moved.data());
        EXPECT_LT(AngularDistance(Eigen::Quaterniond(moved), Eigen::Quaterniond(q)), 2e-3) << t0 << " " << t1;
        double jacobian[8];
        manifold.PlusJacobian(q.data(), jacobian);
        for (int i = 0; i < 2; ++i) {
          double plus_h[2] = {0.0, 0.0}, minus_h[2] = {0.0, 0.0};
          plus_h[i] = 1e-6;
          minus_h[i] = -1e-6;
          Eigen::Vector4d a, b;
          manifold.Plus(q.data(), plus_h, a.data());
          manifold.Plus(q.data(), minus_h, b.data());
          const Eigen::Vector4d numeric = (a - b) / 2e-6;
          for (int r = 0; r < 4; ++r) EXPECT_NEAR(jacobian[r * 2 + i], numeric[r], 1e-8) << t0 << " " << t1;
        }
      }
    }
  }
}

TEST(DofQuaternionManifold, StaysOnTheEulerSetOfItsAxes) {
  // Knee (one axis) and a two-dof joint (Rz Rx, as an ASF "dof rx rz"): after many
  // steps the rotation still has exactly the form R_a0(t0) R_a1(t1).
  DofQuaternionManifold knee({0}), two({2, 0});
  Eigen::Vector4d q = Eigen::Quaterniond::Identity().coeffs(), r = q;
  for (double step : {0.3, -0.1, 0.7}) {
    Eigen::Vector4d next;
    knee.Plus(q.data(), &step, next.data());
    q = next;
    const double steps[2] = {step, -0.5 * step};
    two.Plus(r.data(), steps, next.data());
    r = next;
  }
  const Eigen::Vector3d v = LogMap(Eigen::Quaterniond(q));
  EXPECT_NEAR(v.x(), 0.9, 1e-14);
  EXPECT_NEAR(v.y(), 0.0, 1e-15);
  EXPECT_NEAR(v.z(), 0.0, 1e-15);
  const Eigen::Quaterniond expected = QuaternionFromEuler(Eigen::Vector3d(0.9, -0.45, 0.0), EulerOrder::kZXY);
  EXPECT_LT(AngularDistance(Eigen::Quaterniond(r), expected), 1e-14);
}

}  // namespace
}  // namespace mocapsolve
