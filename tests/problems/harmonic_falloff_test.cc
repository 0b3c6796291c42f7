// HarmonicEdgeResidual (GradientChecker, central differences, autodiff twin) and the
// harmonic falloff solve against a dense solve of the Laplacian system.
#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include <ceres/autodiff_cost_function.h>
#include <ceres/gradient_checker.h>
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "problems/edit_propagation/harmonic_falloff.h"
#include "problems/edit_propagation/harmonic_residual.h"

namespace mocapsolve {
namespace {

TEST(HarmonicEdgeResidualTest, JacobianThreeWays) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-2.0, 2.0);
  // Kernels from 0 (disconnected edge) through tiny to 1 (identical poses); u equal and not.
  const double kernels[] = {0.0, 1e-12, 0.3, 1.0};
  for (double kernel : kernels) {
    for (int trial = 0; trial < 6; ++trial) {
      double u_i = value(rng), u_j = trial == 0 ? u_i : value(rng);
      const double* parameters[] = {&u_i, &u_j};
      HarmonicEdgeResidual analytic(kernel);

      // 1. ceres::GradientChecker (numeric differentiation by Ceres).
      ceres::NumericDiffOptions options;
      const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
      ceres::GradientChecker checker(&analytic, no_manifolds, options);
      ceres::GradientChecker::ProbeResults results;
      // 1e-9 relative: the residual is linear, so numeric derivatives are exact to round-off.
      EXPECT_TRUE(checker.Probe(parameters, 1e-9, &results)) << results.error_log;

      double residual = 0.0, jacobian_i = 0.0, jacobian_j = 0.0;
      double* jacobians[] = {&jacobian_i, &jacobian_j};
      ASSERT_TRUE(analytic.Evaluate(parameters, &residual, jacobians));

      // 2. Central differences by hand.
      const double h = 1e-6;
      for (int block = 0; block < 2; ++block) {
        double plus_u[2] = {u_i, u_j}, minus_u[2] = {u_i, u_j};
        plus_u[block] += h;
        minus_u[block] -= h;
        const double* plus[] = {&plus_u[0], &plus_u[1]};
        const double* minus[] = {&minus_u[0], &minus_u[1]};
        double r_plus = 0.0, r_minus = 0.0;
        ASSERT_TRUE(analytic.Evaluate(plus, &r_plus, nullptr));
        ASSERT_TRUE(analytic.Evaluate(minus, &r_minus, nullptr));
        // 1e-8: central differences of a linear function, error from round-off / h only.
        EXPECT_NEAR((r_plus - r_minus) / (2.0 * h), block == 0 ? jacobian_i : jacobian_j, 1e-8);
      }

      // 3. Autodiff twin: residual and Jacobians equal.
      ceres::AutoDiffCostFunction<HarmonicEdgeFunctor, 1, 1, 1> twin(new HarmonicEdgeFunctor(kernel));
      double twin_residual = 0.0, twin_i = 0.0, twin_j = 0.0;
      double* twin_jacobians[] = {&twin_i, &twin_j};
      ASSERT_TRUE(twin.Evaluate(parameters, &twin_residual, twin_jacobians));
      EXPECT_NEAR(residual, twin_residual, 1e-12);  // Same formula: round-off only.
      EXPECT_NEAR(jacobian_i, twin_i, 1e-12);
      EXPECT_NEAR(jacobian_j, twin_j, 1e-12);
      EXPECT_NEAR(residual, std::sqrt(kernel) * (u_i - u_j), 1e-12);

      // Null Jacobian pointers are allowed per block.
      double* partial[] = {nullptr, &jacobian_j};
      EXPECT_TRUE(analytic.Evaluate(parameters, &residual, partial));
    }
  }
}

// Random points on a noisy circle (a "periodic motion"), kNN graph.
Eigen::MatrixXd CircleFeatures(int n, std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, 0.05);
  Eigen::MatrixXd features(n, 3);
  for (int i = 0; i < n; ++i) {
    const double phase = 2.0 * 3.14159265358979 * 3.0 * i / n;  // Three cycles.
    features.row(i) << std::cos(phase) + noise(*rng), std::sin(phase) + noise(*rng), noise(*rng);
  }
  return features;
}

// The dense solution of L_FF u_F = -L_FL y_L, L = D - K.
Eigen::VectorXd DenseHarmonic(int n, const std::vector<WeightedEdge>& edges,
                              const std::vector<std::pair<int, double>>& labels) {
  Eigen::MatrixXd laplacian = Eigen::MatrixXd::Zero(n, n);
  for (const WeightedEdge& e : edges) {
    laplacian(e.a, e.b) -= e.kernel;
    laplacian(e.b, e.a) -= e.kernel;
    laplacian(e.a, e.a) += e.kernel;
    laplacian(e.b, e.b) += e.kernel;
  }
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  std::vector<bool> fixed(n, false);
  for (const auto& [frame, value] : labels) {
    u[frame] = value;
    fixed[frame] = true;
  }
  std::vector<int> free;
  for (int i = 0; i < n; ++i) {
    if (!fixed[i]) free.push_back(i);
  }
  const int m = static_cast<int>(free.size());
  Eigen::MatrixXd a(m, m);
  Eigen::VectorXd b(m);
  for (int r = 0; r < m; ++r) {
    b[r] = 0.0;
    for (int c = 0; c < n; ++c) {
      if (fixed[c]) b[r] -= laplacian(free[r], c) * u[c];
    }
    for (int c = 0; c < m; ++c) a(r, c) = laplacian(free[r], free[c]);
  }
  const Eigen::VectorXd x = a.ldlt().solve(b);
  for (int r = 0; r < m; ++r) u[free[r]] = x[r];
  return u;
}

TEST(HarmonicFalloffTest, MatchesDenseSolveOfTheLaplacianSystem) {
  std::mt19937 rng(3);
  const int n = 240;
  const Eigen::MatrixXd features = CircleFeatures(n, &rng);
  const std::vector<WeightedEdge> edges = PoseGraphEdges(features, 8, 0.3);
  const std::vector<int> edited = {40, 130};
  const std::vector<int> anchors = {0, n - 1};
  std::vector<Eigen::VectorXd> fields;
  HarmonicReport report;
  ASSERT_TRUE(HarmonicFalloffs(n, edges, edited, anchors, HarmonicOptions(), &fields, &report).ok());
  ASSERT_EQ(fields.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    std::vector<std::pair<int, double>> labels = {{edited[k], 1.0}, {edited[1 - k], 0.0}, {0, 0.0},
                                                  {n - 1, 0.0}};
    const Eigen::VectorXd dense = DenseHarmonic(n, edges, labels);
    // 1e-7: both are direct solves of the same SPD system (Ceres adds a 1e-16 damping).
    EXPECT_LT((fields[k] - dense).cwiseAbs().maxCoeff(), 1e-7) << "field " << k;
    EXPECT_DOUBLE_EQ(fields[k][edited[k]], 1.0);
    EXPECT_DOUBLE_EQ(fields[k][edited[1 - k]], 0.0);
    // Maximum principle: labels are 0 and 1.
    EXPECT_GE(fields[k].minCoeff(), -1e-9);
    EXPECT_LE(fields[k].maxCoeff(), 1.0 + 1e-9);
  }
  // Periodic features: the frame one cycle after the edit (same phase) is reached strongly,
  // the opposite phase weakly.
  EXPECT_GT(fields[0][40 + n / 3], 0.5);
  EXPECT_LT(fields[0][40 + n / 6], fields[0][40 + n / 3]);
  EXPECT_LT(report.max_gradient, 1e-8);
}

TEST(HarmonicFalloffTest, GroundNodeMatchesDenseSolveWithAnExtraLabelledNode) {
  std::mt19937 rng(4);
  const int n = 150;
  const Eigen::MatrixXd features = CircleFeatures(n, &rng);
  const std::vector<WeightedEdge> edges = PoseGraphEdges(features, 6, 0.3);
  HarmonicOptions options;
  options.ground_weight = 0.05;
  std::vector<Eigen::VectorXd> fields;
  ASSERT_TRUE(HarmonicFalloffs(n, edges, {70}, {}, options, &fields, nullptr).ok());
  std::vector<WeightedEdge> grounded = edges;
  for (int f = 0; f < n; ++f) grounded.push_back({f, n, 0.05});
  const Eigen::VectorXd dense = DenseHarmonic(n + 1, grounded, {{70, 1.0}, {n, 0.0}});
  // 1e-7: two direct solves of one SPD system.
  EXPECT_LT((fields[0] - dense.head(n)).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT(fields[0].maxCoeff(), 1.0 + 1e-12);
  EXPECT_GT(fields[0].minCoeff(), 0.0);  // Connected to the edit: strictly positive.
  EXPECT_LT(fields[0][0], 0.5);          // Absorbed far from the edit.
}

TEST(HarmonicFalloffTest, GraphEdgesAreTheExactSymmetrizedKnnPlusTemporalNeighbours) {
  std::mt19937 rng(11);
  const int n = 300;  // More than one Gram block.
  const Eigen::MatrixXd features = CircleFeatures(n, &rng);
  const int knn = 5;
  const double sigma = 0.5;
  const std::vector<WeightedEdge> edges = PoseGraphEdges(features, knn, sigma);
  std::set<std::pair<int, int>> expected;
  for (int i = 0; i < n; ++i) {
    std::vector<std::pair<double, int>> d;
    for (int j = 0; j < n; ++j) {
      if (j != i) d.emplace_back((features.row(i) - features.row(j)).squaredNorm(), j);
    }
    std::sort(d.begin(), d.end());
    for (int k = 0; k < knn; ++k) expected.insert({std::min(i, d[k].second), std::max(i, d[k].second)});
    if (i + 1 < n) expected.insert({i, i + 1});
  }
  std::set<std::pair<int, int>> got;
  for (const WeightedEdge& e : edges) {
    EXPECT_LT(e.a, e.b);
    got.insert({e.a, e.b});
    const double d2 = (features.row(e.a) - features.row(e.b)).squaredNorm();
    EXPECT_NEAR(e.kernel, std::max(1e-300, std::exp(-d2 / (2 * sigma * sigma))), 1e-15);
  }
  EXPECT_EQ(got.size(), edges.size());  // Each edge once.
  EXPECT_EQ(got, expected);
}

TEST(HarmonicFalloffTest, BadInputIsAnError) {
  std::vector<Eigen::VectorXd> fields;
  EXPECT_FALSE(SolveHarmonicFields(3, {{0, 3, 1.0}}, {{{0, 1.0}}}, HarmonicOptions(), &fields, nullptr).ok());
  EXPECT_FALSE(SolveHarmonicFields(3, {{0, 1, 1.0}}, {{}}, HarmonicOptions(), &fields, nullptr).ok());
  EXPECT_FALSE(SolveHarmonicFields(3, {{0, 1, 1.0}}, {{{5, 1.0}}}, HarmonicOptions(), &fields, nullptr).ok());
  HarmonicOptions bad;
  bad.max_iterations = 0;
  EXPECT_FALSE(SolveHarmonicFields(3, {{0, 1, 1.0}}, {{{0, 1.0}}}, bad, &fields, nullptr).ok());
}

}  // namespace
}  // namespace mocapsolve
