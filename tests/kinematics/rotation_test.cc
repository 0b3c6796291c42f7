#include "kinematics/rotation.h"

#include <random>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

constexpr EulerOrder kAllOrders[] = {EulerOrder::kXYZ, EulerOrder::kXZY, EulerOrder::kYXZ,
                                     EulerOrder::kYZX, EulerOrder::kZXY, EulerOrder::kZYX};

Eigen::Quaterniond RandomRotation(std::mt19937* rng) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(*rng), normal(*rng), normal(*rng), normal(*rng));
  return q.normalized();
}

TEST(EulerOrder, ParsesAndNames) {
  for (EulerOrder order : kAllOrders) {
    EulerOrder parsed;
    ASSERT_TRUE(ParseEulerOrder(EulerOrderName(order), &parsed));
    EXPECT_EQ(parsed, order);
  }
  EulerOrder order;
  EXPECT_TRUE(ParseEulerOrder("zxy", &order));
  EXPECT_EQ(order, EulerOrder::kZXY);
  EXPECT_FALSE(ParseEulerOrder("XXY", &order));
  EXPECT_FALSE(ParseEulerOrder("XYZW", &order));
  EXPECT_FALSE(ParseEulerOrder("ABC", &order));
}

TEST(Euler, IntrinsicProductInNamedOrder) {
  // ZXY with (a, b, c) is Rz(a) Rx(b) Ry(c), as BVH's "Zrotation Xrotation Yrotation".
  const Eigen::Vector3d angles(0.3, -0.7, 1.1);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-0.7, Eigen::Vector3d::UnitX()) *
                                    Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitY()))
                                       .toRotationMatrix();
  EXPECT_TRUE(QuaternionFromEuler(angles, EulerOrder::kZXY).toRotationMatrix().isApprox(expected, 1e-14));
}

TEST(Euler, RoundTripsAllOrders) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> outer(-3.1, 3.1), middle(-1.5, 1.5);
  for (EulerOrder order : kAllOrders) {
    for (int trial = 0; trial < 200; ++trial) {
      const Eigen::Vector3d angles(outer(rng), middle(rng), outer(rng));
      const Eigen::Vector3d back = EulerFromQuaternion(QuaternionFromEuler(angles, order), order);
      // Angles are unique with the middle one inside (-pi/2, pi/2): compare directly.
      EXPECT_LT((back - angles).norm(), 1e-9) << EulerOrderName(order);
    }
  }
}

TEST(Euler, GimbalLockStillReproducesTheRotation) {
  for (EulerOrder order : kAllOrders) {
    for (double middle : {kPi / 2, -kPi / 2, kPi / 2 - 1e-9}) {
      const Eigen::Quaterniond q = QuaternionFromEuler(Eigen::Vector3d(0.4, middle, -1.2), order);
      const Eigen::Quaterniond back = QuaternionFromEuler(EulerFromQuaternion(q, order), order);
      // At and near lock only a +- c is determined; the rotation must still match to
      // round-off (a few 1e-16, times the ~1e-8 sqrt sensitivity near the lock).
      EXPECT_LT(AngularDistance(q, back), 1e-12) << EulerOrderName(order) << " " << middle;
    }
  }
}

TEST(ExpLog, InverseOfEachOtherIncludingNearZeroAndPi) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  for (double angle : {0.0, 1e-12, 1e-8, 1e-5, 0.1, 1.0, 3.0, kPi - 1e-6, kPi - 1e-10, kPi}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Vector3d axis = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      const Eigen::Vector3d v = angle * axis;
      const Eigen::Quaterniond q = ExpMap(v);
      EXPECT_NEAR(q.norm(), 1.0, 1e-15);
      // Exp against Eigen's AngleAxis.
      EXPECT_LT(AngularDistance(q, Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis))), 1e-12);
      const Eigen::Vector3d back = LogMap(q);
      if (angle < kPi - 1e-6) {
        EXPECT_LT((back - v).norm(), 1e-12 * std::max(1.0, angle)) << angle;
      } else {
        // Near pi, v and -v (nearly) name the same rotation: compare rotations.
        EXPECT_LT(AngularDistance(ExpMap(back), q), 1e-9) << angle;
        EXPECT_NEAR(back.norm(), angle, 1e-6);
      }
    }
  }
}

TEST(ExpLog, LogTakesTheShortWayForNegativeW) {
  const Eigen::Quaterniond q = ExpMap(Eigen::Vector3d(0.2, 0.0, 0.0));
  const Eigen::Quaterniond minus_q(-q.coeffs());
  EXPECT_LT((LogMap(minus_q) - Eigen::Vector3d(0.2, 0.0, 0.0)).norm(), 1e-14);
}

TEST(ExpLog, SmallAngleTaylorBranchIsAccurate) {
  // Compare the branch with the closed form just outside it.
  const Eigen::Vector3d v(3e-7, -2e-7, 1e-7);
  const double theta = v.norm();
  const Eigen::Quaterniond q = ExpMap(v);
  EXPECT_NEAR(q.w(), std::cos(theta / 2), 1e-16);
  EXPECT_NEAR(q.x(), std::sin(theta / 2) / theta * v.x(), 1e-22);
}

TEST(SignContinuity, FlipsToTheNearHemisphere) {
  std::mt19937 rng(3);
  std::vector<Eigen::Quaterniond> series;
  Eigen::Quaterniond q = RandomRotation(&rng);
  for (int i = 0; i < 50; ++i) {
    q = q * ExpMap(Eigen::Vector3d(0.1, 0.05, -0.08));
    series.push_back(i % 3 == 0 ? Eigen::Quaterniond(-q.coeffs()) : q);
  }
  MakeSignContinuous(&series);
  for (size_t i = 1; i < series.size(); ++i) EXPECT_GT(series[i].dot(series[i - 1]), 0.0);
  // Still the same rotations.
  EXPECT_LT(AngularDistance(series.back(), q), 1e-12);
}

}  // namespace
}  // namespace mocapsolve
