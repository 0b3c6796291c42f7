#include "solvers/dls_solver.h"

#include <random>

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include "kinematics/rotation.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

// r = y - exp(a t + b), a Euclidean curve fit (Ceres' curve_fitting example).
class ExponentialResidual : public ceres::SizedCostFunction<1, 2> {
 public:
  ExponentialResidual(double t, double y) : t_(t), y_(y) {}
  bool Evaluate(double const* const* p, double* r, double** j) const override {
    const double e = std::exp(p[0][0] * t_ + p[0][1]);
    r[0] = y_ - e;
    if (j != nullptr && j[0] != nullptr) {
      j[0][0] = -t_ * e;
      j[0][1] = -e;
    }
    return true;
  }

 private:
  double t_, y_;
};

// r = R(q) a - b for a unit quaternion q (x, y, z, w) on RightQuaternionManifold.
class RotatedPointResidual : public ceres::SizedCostFunction<3, 4> {
 public:
  RotatedPointResidual(Eigen::Vector3d a, Eigen::Vector3d b) : a_(a), b_(b) {}
  bool Evaluate(double const* const* p, double* r, double** j) const override {
    Eigen::Quaterniond q = Eigen::Map<const Eigen::Quaterniond>(p[0]);
    const double norm = q.norm();
    q.coeffs() /= norm;
    const Eigen::Vector3d ra = q * a_;
    Eigen::Map<Eigen::Vector3d> residual(r);
    residual = ra - b_;
    if (j != nullptr && j[0] != nullptr) {
      // d(R exp(d) a)/dd = -R [a]x.
      const Eigen::Matrix3d tangent = -q.toRotationMatrix() * SkewSymmetric(a_);
      Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> ambient(j[0]);
      ambient = tangent * AmbientFromTangent(q.coeffs().data()) / norm;
    }
    return true;
  }

 private:
  Eigen::Vector3d a_, b_;
};

TEST(DlsSolver, FitsACurveLikeCeres) {
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<std::unique_ptr<ExponentialResidual>> costs;
  for (int i = 0; i < 40; ++i) {
    const double t = i / 10.0;
    costs.emplace_back(new ExponentialResidual(t, std::exp(0.3 * t + 0.1) + noise(rng)));
  }
  double dls_x[2] = {0.0, 0.0};
  DlsProblem dls;
  dls.AddParameterBlock(dls_x, 2);
  for (auto& c : costs) dls.AddResidualBlock(c.get(), nullptr, {0});
  DlsSolver solver;
  DlsSummary summary;
  DlsOptions options;
  solver.Solve(options, &dls, &summary);
  EXPECT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
  EXPECT_NE(summary.termination, DlsTermination::kNoConvergence) << summary.BriefReport();

  double ceres_x[2] = {0.0, 0.0};
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (auto& c : costs) problem.AddResidualBlock(c.get(), nullptr, ceres_x);
  ceres::Solver::Options ceres_options;
  ceres_options.function_tolerance = 1e-12;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(ceres_options, &problem, &ceres_summary);
  // Same minimum: parameters to 1e-6, cost to 1e-9 relative.
  EXPECT_NEAR(dls_x[0], ceres_x[0], 1e-6);
  EXPECT_NEAR(dls_x[1], ceres_x[1], 1e-6);
  EXPECT_NEAR(summary.final_cost, ceres_summary.final_cost, 1e-9 * ceres_summary.final_cost);
  EXPECT_NEAR(summary.initial_cost, ceres_summary.initial_cost, 1e-9 * ceres_summary.initial_cost);
}

TEST(DlsSolver, RecoversARotationOnTheManifold) {
  const Eigen::Quaterniond truth = ExpMap(Eigen::Vector3d(0.4, -1.1, 2.5));
  std::mt19937 rng(2);
  std::normal_distribution<double> normal;
  std::vector<std::unique_ptr<RotatedPointResidual>> costs;
  for (int i = 0; i < 5; ++i) {
    const Eigen::Vector3d a(normal(rng), normal(rng), normal(rng));
    costs.emplace_back(new RotatedPointResidual(a, truth * a));
  }
  RightQuaternionManifold manifold;
  for (bool adaptive : {true, false}) {
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    DlsProblem problem;
    problem.AddParameterBlock(q.coeffs().data(), 4, &manifold);
    for (auto& c : costs) problem.AddResidualBlock(c.get(), nullptr, {0});
    DlsOptions options;
    options.adaptive_damping = adaptive;
    options.lambda = adaptive ? 1e-3 : 1e-2;
    options.max_iterations = 100;
    DlsSolver solver;
    DlsSummary summary;
    solver.Solve(options, &problem, &summary);
    EXPECT_LT(AngularDistance(q, truth), 1e-8) << summary.BriefReport();
    EXPECT_NEAR(q.norm(), 1.0, 1e-12);
    EXPECT_LT(summary.final_cost, 1e-16) << summary.BriefReport();
  }
}

TEST(DlsSolver, UnderdeterminedUsesTheJJtFormAndFindsAZero) {
  // One residual row over a 2-vector: m = 1 < n = 2, so the step is eq. 4 as written.
  struct Line : public ceres::SizedCostFunction<1, 2> {
    bool Evaluate(double const* const* p, double* r, double** j) const override {
      r[0] = p[0][0] + 2.0 * p[0][1] - 4.0;
      if (j != nullptr && j[0] != nullptr) {
        j[0][0] = 1.0;
        j[0][1] = 2.0;
      }
      return true;
    }
  } line;
  double x[2] = {0.0, 0.0};
  DlsProblem problem;
  problem.AddParameterBlock(x, 2);
  problem.AddResidualBlock(&line, nullptr, {0});
  DlsSolver solver;
  DlsSummary summary;
  solver.Solve(DlsOptions(), &problem, &summary);
  EXPECT_NEAR(x[0] + 2 * x[1], 4.0, 1e-6);
  // DLS from zero returns (nearly) the minimum-norm solution (0.8, 1.6).
  EXPECT_NEAR(x[0], 0.8, 1e-3);
  EXPECT_NEAR(x[1], 1.6, 1e-3);
}

TEST(DlsSolver, RobustLossDownweightsAnOutlier) {
  std::vector<std::unique_ptr<ExponentialResidual>> costs;
  for (int i = 0; i < 30; ++i) {
    const double t = i / 10.0;
    costs.emplace_back(new ExponentialResidual(t, std::exp(0.3 * t + 0.1) + (i == 15 ? 5.0 : 0.0)));
  }
  ceres::CauchyLoss loss(0.1);
  double x[2] = {0.0, 0.0};
  DlsProblem problem;
  problem.AddParameterBlock(x, 2);
  for (auto& c : costs) problem.AddResidualBlock(c.get(), &loss, {0});
  DlsSolver solver;
  DlsSummary summary;
  DlsOptions options;
  options.max_iterations = 200;
  solver.Solve(options, &problem, &summary);
  EXPECT_NEAR(x[0], 0.3, 2e-3) << summary.BriefReport();
  EXPECT_NEAR(x[1], 0.1, 2e-3);
}

TEST(DlsOptions, Validation) {
  DlsOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.lambda_decrease = 2.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("lambda_decrease"), std::string::npos);
  options = DlsOptions();
  options.adaptive_damping = false;
  options.lambda = 0.0;
  EXPECT_FALSE(options.IsValid(&error));
}

}  // namespace
}  // namespace mocapsolve
