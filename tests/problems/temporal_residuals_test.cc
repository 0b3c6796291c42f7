// FiniteDifferenceResidual and the pose priors: GradientChecker on the manifold and
// autodiff twins.
#include <random>

#include <ceres/autodiff_cost_function.h>
#include <ceres/dynamic_autodiff_cost_function.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include "kinematics/rotation.h"
#include "problems/marker_solve/finite_difference_residual.h"
#include "problems/marker_solve/pose_prior_residual.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

// Twin of FiniteDifferenceResidual, written from its header's formula.
struct FiniteDifferenceTwin {
  std::vector<double> c;
  bool quaternion;
  double weight;
  template <typename T>
  bool operator()(T const* const* x, T* r) const {
    const int size = quaternion ? 4 : 3;
    const int n = static_cast<int>(c.size());
    for (int k = 0; k < size; ++k) r[k] = T(0.0);
    for (int i = 0; i < n; ++i) {
      T sign(1.0);
      if (quaternion) {
        T dot(0.0);
        for (int k = 0; k < 4; ++k) dot += x[i][k] * x[n - 1][k];
        if (dot < T(0.0)) sign = T(-1.0);
      }
      for (int k = 0; k < size; ++k) r[k] += T((quaternion ? 2.0 : 1.0) * weight * c[i]) * sign * x[i][k];
    }
    return true;
  }
};

// Compares an analytic cost function with its twin and with GradientChecker.
void ExpectJacobiansMatch(const ceres::CostFunction& analytic, const ceres::CostFunction& twin,
                          const std::vector<const double*>& parameters,
                          const std::vector<const ceres::Manifold*>& manifolds) {
  const int nr = analytic.num_residuals();
  ASSERT_EQ(nr, twin.num_residuals());
  const auto& sizes = analytic.parameter_block_sizes();
  std::vector<std::vector<double>> ja(sizes.size()), jt(sizes.size());
  std::vector<double*> pa, pt;
  for (size_t b = 0; b < sizes.size(); ++b) {
    ja[b].assign(nr * sizes[b], 0.0);
    jt[b].assign(nr * sizes[b], 0.0);
    pa.push_back(ja[b].data());
    pt.push_back(jt[b].data());
  }
  std::vector<double> ra(nr), rt(nr);
  ASSERT_TRUE(analytic.Evaluate(parameters.data(), ra.data(), pa.data()));
  ASSERT_TRUE(twin.Evaluate(parameters.data(), rt.data(), pt.data()));
  for (int i = 0; i < nr; ++i) EXPECT_NEAR(ra[i], rt[i], 1e-12);  // Same arithmetic.
  for (size_t b = 0; b < sizes.size(); ++b) {
    for (size_t k = 0; k < ja[b].size(); ++k) EXPECT_NEAR(ja[b][k], jt[b][k], 1e-12);
  }
  ceres::NumericDiffOptions options;
  ceres::GradientChecker checker(&analytic, &manifolds, options);
  ceres::GradientChecker::ProbeResults results;
  checker.Probe(parameters.data(), 1e-7, &results);
  ASSERT_TRUE(results.return_value);
  for (size_t b = 0; b < results.local_jacobians.size(); ++b) {
    // Linear residuals: central differences are exact up to round-off (mixed tolerance
    // because many entries are exactly zero).
    EXPECT_LT((results.local_jacobians[b] - results.local_numeric_jacobians[b]).cwiseAbs().maxCoeff(), 1e-8)
        << results.error_log;
  }
}

TEST(FiniteDifferenceResidual, RotationsAndTranslationsBothOrders) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  RightQuaternionManifold manifold;
  for (SmoothnessOrder order : {SmoothnessOrder::kVelocity, SmoothnessOrder::kAcceleration}) {
    const int n = static_cast<int>(order) + 1;
    for (bool quaternion : {true, false}) {
      std::vector<Eigen::Vector4d> values(n);
      Eigen::Quaterniond q = ExpMap(Eigen::Vector3d(0.3, 1.0, -0.2));
      for (int i = 0; i < n; ++i) {
        q = q * ExpMap(0.1 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)));
        values[i] = quaternion ? Eigen::Vector4d(q.coeffs()) : Eigen::Vector4d(normal(rng), normal(rng), normal(rng), 0.0);
      }
      if (quaternion) values[0] = -values[0];  // A sign flip the residual must see through.
      FiniteDifferenceResidual analytic(order, quaternion, 3.0);
      auto* twin_functor = new FiniteDifferenceTwin{order == SmoothnessOrder::kVelocity ? std::vector<double>{-1, 1} : std::vector<double>{1, -2, 1}, quaternion, 3.0};
      ceres::DynamicAutoDiffCostFunction<FiniteDifferenceTwin, 4> twin(twin_functor);
      std::vector<const double*> parameters;
      std::vector<const ceres::Manifold*> manifolds;
      for (int i = 0; i < n; ++i) {
        twin.AddParameterBlock(quaternion ? 4 : 3);
        parameters.push_back(values[i].data());
        manifolds.push_back(quaternion ? &manifold : nullptr);
      }
      twin.SetNumResiduals(quaternion ? 4 : 3);
      ExpectJacobiansMatch(analytic, twin, parameters, manifolds);
    }
  }
}

TEST(FiniteDifferenceResidual, ChordalVelocityApproximatesTheAngle) {
  const Eigen::Quaterniond a = ExpMap(Eigen::Vector3d(0.2, -0.4, 1.0));
  const Eigen::Quaterniond b = a * ExpMap(Eigen::Vector3d(0.0, 0.01, 0.0));
  FiniteDifferenceResidual velocity(SmoothnessOrder::kVelocity, true, 1.0);
  const double* parameters[] = {a.coeffs().data(), b.coeffs().data()};
  double r[4];
  ASSERT_TRUE(velocity.Evaluate(parameters, r, nullptr));
  // 4 sin(theta / 4) for theta = 0.01 rad.
  EXPECT_NEAR(Eigen::Map<Eigen::Vector4d>(r).norm(), 4 * std::sin(0.01 / 4), 1e-12);
}

struct RotationPriorTwin {
  Eigen::Vector4d reference;
  double weight;
  template <typename T>
  bool operator()(const T* q, T* r) const {
    T dot(0.0);
    for (int k = 0; k < 4; ++k) dot += q[k] * reference[k];
    const T sign = dot < T(0.0) ? T(-1.0) : T(1.0);
    for (int k = 0; k < 4; ++k) r[k] = T(2.0 * weight) * (q[k] - sign * reference[k]);
    return true;
  }
};

// Twin of the anisotropic rotation prior, from the header's formula: b = q_ref (x) (u, 0) by
// Eigen's quaternion product, r = 2 [w I + (w_u - w) b b^T] (q - s q_ref).
struct AxisRotationPriorTwin {
  Eigen::Vector4d reference;
  Eigen::Vector3d axis;
  double weight, axis_weight;
  template <typename T>
  bool operator()(const T* q, T* r) const {
    const Eigen::Quaterniond ref(reference[3], reference[0], reference[1], reference[2]);
    const Eigen::Vector4d b = (ref * Eigen::Quaterniond(0.0, axis.x(), axis.y(), axis.z())).coeffs();
    T dot(0.0);
    for (int k = 0; k < 4; ++k) dot += q[k] * reference[k];
    const T sign = dot < T(0.0) ? T(-1.0) : T(1.0);
    T along(0.0);
    for (int k = 0; k < 4; ++k) along += b[k] * (q[k] - sign * reference[k]);
    for (int k = 0; k < 4; ++k) {
      r[k] = T(2.0 * weight) * (q[k] - sign * reference[k]) + T(2.0 * (axis_weight - weight) * b[k]) * along;
    }
    return true;
  }
};

struct TranslationPriorTwin {
  Eigen::Vector3d reference;
  double weight;
  template <typename T>
  bool operator()(const T* t, T* r) const {
    for (int k = 0; k < 3; ++k) r[k] = T(weight) * (t[k] - reference[k]);
    return true;
  }
};

TEST(PosePriors, MatchTwinsAndNumericDerivatives) {
  RightQuaternionManifold manifold;
  // References (the previous frame, or a subject's mean pose as the rest prior's): a generic
  // rotation, one 3.11 rad from the identity, one on the far hemisphere of every point
  // (s = -1). Each has |q . q_ref| >= 0.43 with every point: the checker's differences
  // crossed the s flip (where the residual jumps) at |q . q_ref| <= 0.11.
  for (const Eigen::Vector3d& r : {Eigen::Vector3d(1.0, 0.5, -0.3), Eigen::Vector3d(2.2, 2.2, 0.0), Eigen::Vector3d(-2.3, -1.7, 0.7)}) {
    const Eigen::Vector4d reference = ExpMap(r).coeffs();
    for (const Eigen::Vector3d& v : {Eigen::Vector3d(1.0, 0.5, -0.3), Eigen::Vector3d(0.1, 2.0, 0.3), Eigen::Vector3d(kPi - 1e-6, 0, 0)}) {
      const Eigen::Vector4d q = ExpMap(v).coeffs();
      SCOPED_TRACE(::testing::Message() << "reference " << r.transpose() << ", q " << v.transpose());
      RotationPriorResidual analytic(reference.data(), 1.5);
      ceres::AutoDiffCostFunction<RotationPriorTwin, 4, 4> twin(new RotationPriorTwin{reference, 1.5});
      ExpectJacobiansMatch(analytic, twin, {q.data()}, {&manifold});
      // With an axis (the twist about a marker's direction): weight 40 about it, 1.5 else.
      const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.8, 0.5).normalized();
      RotationPriorResidual anisotropic(reference.data(), 1.5);
      anisotropic.set_axis(axis.data(), 40.0);
      ceres::AutoDiffCostFunction<AxisRotationPriorTwin, 4, 4> axis_twin(
          new AxisRotationPriorTwin{reference, axis, 1.5, 40.0});
      ExpectJacobiansMatch(anisotropic, axis_twin, {q.data()}, {&manifold});
    }
  }
  const Eigen::Vector3d t_ref(1, 2, 3), t(0.5, -1, 4);
  TranslationPriorResidual analytic(t_ref.data(), 0.7);
  ceres::AutoDiffCostFunction<TranslationPriorTwin, 3, 3> twin(new TranslationPriorTwin{t_ref, 0.7});
  ExpectJacobiansMatch(analytic, twin, {t.data()}, {nullptr});
}

// The axis weight prices the twist about u alone: a turn of q_ref about u costs weight_u per
// radian, a turn about a normal direction weight, and clearing the axis restores the isotropic
// residual bit for bit.
TEST(PosePriors, AxisWeightActsOnTheTwistOnly) {
  const Eigen::Quaterniond reference = ExpMap(Eigen::Vector3d(0.4, -1.1, 0.7));
  const Eigen::Vector3d u = Eigen::Vector3d(1.0, 2.0, -0.5).normalized();
  const Eigen::Vector3d normal = u.unitOrthogonal();
  RotationPriorResidual prior(reference.coeffs().data(), 2.0);
  prior.set_axis(u.data(), 50.0);
  auto cost = [&](const Eigen::Quaterniond& q) {
    Eigen::Vector4d r;
    const double* parameters[] = {q.coeffs().data()};
    EXPECT_TRUE(prior.Evaluate(parameters, r.data(), nullptr));
    return r.norm();
  };
  const double angle = 1e-4;
  EXPECT_NEAR(cost(reference * ExpMap(angle * u)), 50.0 * angle, 1e-9);
  EXPECT_NEAR(cost(reference * ExpMap(angle * normal)), 2.0 * angle, 1e-9);
  const Eigen::Quaterniond q = reference * ExpMap(Eigen::Vector3d(0.2, 0.1, -0.3));
  prior.clear_axis();
  RotationPriorResidual isotropic(reference.coeffs().data(), 2.0);
  Eigen::Vector4d a, b;
  const double* parameters[] = {q.coeffs().data()};
  ASSERT_TRUE(prior.Evaluate(parameters, a.data(), nullptr));
  ASSERT_TRUE(isotropic.Evaluate(parameters, b.data(), nullptr));
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace mocapsolve
