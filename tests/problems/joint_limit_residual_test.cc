// JointLimitResidual: the hinge on Euler angles against an autodiff twin (angles from
// the rotation matrix entries, templated) and central differences taken with the
// joint's manifold Plus. (GradientChecker's ambient-space differences disagreed with
// both by 1e-5..1e-3 here while the twin and the manifold differences agree to 1e-10 and
// 1e-7; not yet understood, noted in the issue.)
#include "problems/marker_solve/joint_limit_residual.h"

#include <ceres/dynamic_autodiff_cost_function.h>
#include <ceres/rotation.h>
#include <gtest/gtest.h>

#include "kinematics/rotation.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

// Twin: rotation matrix from the normalized quaternion, Euler angles of the completed
// 3-axis order by the closed form of EulerFromMatrix, the first k of them hinged.
struct JointLimitTwin {
  std::vector<int> axes;
  std::vector<std::pair<double, double>> limits;
  double weight;
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    const T wxyz[4] = {p[0][3], p[0][0], p[0][1], p[0][2]};
    T m[9];
    ceres::QuaternionToRotation(wxyz, m);  // Row-major, normalizes.
    auto M = [&](int row, int col) { return m[3 * row + col]; };
    const int i = axes[0];
    const int j = axes.size() > 1 ? axes[1] : (i + 1) % 3;
    const int k = axes.size() > 2 ? axes[2] : 3 - i - j;
    const double s = ((j - i + 3) % 3 == 1) ? 1.0 : -1.0;
    T t[3];
    if (axes.size() == 1) {
      t[0] = T(2.0) * atan2(p[0][i], p[0][3]);
    } else {
      t[1] = atan2(T(s) * M(i, k), sqrt(M(i, i) * M(i, i) + M(i, j) * M(i, j)));
      t[2] = atan2(T(-s) * M(i, j), M(i, i));
      t[0] = atan2(T(-s) * M(j, k), M(k, k));
    }
    for (size_t n = 0; n < axes.size(); ++n) {
      const T above = t[n] - T(limits[n].second), below = t[n] - T(limits[n].first);
      r[n] = T(weight) * (above > T(0.0) ? above : below < T(0.0) ? below : T(0.0));
    }
    return true;
  }
};

TEST(JointLimitResidual, MatchesTwinAndNumericDerivatives) {
  struct Case {
    std::vector<int> axes;
    Eigen::Vector3d angles;  // In product order (only the first k used).
  };
  const std::vector<std::pair<double, double>> limits3 = {{-0.5, 0.4}, {-0.2, 0.3}, {-1.0, 1.0}};
  const std::vector<Case> cases = {
      {{0}, {0.9, 0, 0}},           // Knee past its upper limit.
      {{0}, {-0.7, 0, 0}},          // Below.
      {{0}, {0.1, 0, 0}},           // Inside: zero residual and Jacobian.
      {{2, 0}, {0.8, -0.6, 0}},     // Two dofs, both outside.
      {{2, 1, 0}, {0.7, 0.5, -1.3}},  // Three dofs.
  };
  for (const Case& c : cases) {
    const int k = static_cast<int>(c.axes.size());
    std::vector<std::pair<double, double>> limits(limits3.begin(), limits3.begin() + k);
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    for (int n = 0; n < k; ++n) {
      q = q * Eigen::Quaterniond(Eigen::AngleAxisd(c.angles[n], Eigen::Vector3d::Unit(c.axes[n])));
    }
    JointLimitResidual analytic(c.axes, limits, 2.0);
    ceres::DynamicAutoDiffCostFunction<JointLimitTwin, 4> twin(new JointLimitTwin{c.axes, limits, 2.0});
    twin.AddParameterBlock(4);
    twin.SetNumResiduals(k);
    const double* parameters[] = {q.coeffs().data()};
    double r[3], rt[3], j[12], jt[12];
    double* jp[] = {j};
    double* jtp[] = {jt};
    ASSERT_TRUE(analytic.Evaluate(parameters, r, jp));
    ASSERT_TRUE(twin.Evaluate(parameters, rt, jtp));
    for (int n = 0; n < k; ++n) EXPECT_NEAR(r[n], rt[n], 1e-12);  // Same angles, two routes.
    for (int n = 0; n < 4 * k; ++n) EXPECT_NEAR(j[n], jt[n], 1e-10) << n;  // Exact both.
    for (int n = 0; n < k; ++n) {
      const double t = c.angles[n];
      const double expected = t > limits[n].second ? t - limits[n].second : t < limits[n].first ? t - limits[n].first : 0.0;
      EXPECT_NEAR(r[n], 2.0 * expected, 1e-12);
    }
    // Central differences on the manifold, Plus(q, +-h e_i), against the analytic
    // Jacobian mapped to the tangent by the manifold's PlusJacobian.
    const ceres::Manifold* manifold = RotationManifold(c.axes);
    Eigen::Matrix<double, 4, Eigen::Dynamic, Eigen::RowMajor> plus_jacobian(4, k);
    manifold->PlusJacobian(q.coeffs().data(), plus_jacobian.data());
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>> ambient(j, k, 4);
    const Eigen::MatrixXd tangent = ambient * plus_jacobian;
    const double h = 1e-6;
    for (int i = 0; i < k; ++i) {
      Eigen::VectorXd step = Eigen::VectorXd::Zero(k);
      step[i] = h;
      Eigen::Vector4d plus, minus;
      manifold->Plus(q.coeffs().data(), step.data(), plus.data());
      step[i] = -h;
      manifold->Plus(q.coeffs().data(), step.data(), minus.data());
      double rp[3], rm[3];
      const double* pp[] = {plus.data()};
      const double* pm[] = {minus.data()};
      ASSERT_TRUE(analytic.Evaluate(pp, rp, nullptr));
      ASSERT_TRUE(analytic.Evaluate(pm, rm, nullptr));
      for (int n = 0; n < k; ++n) {
        // Smooth away from the kinks: central differences good to ~1e-9 here.
        EXPECT_NEAR(tangent(n, i), (rp[n] - rm[n]) / (2 * h), 1e-7) << "row " << n << " dof " << i;
      }
    }
  }
}

}  // namespace
}  // namespace mocapsolve
