#include "solvers/right_quaternion_manifold.h"

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
