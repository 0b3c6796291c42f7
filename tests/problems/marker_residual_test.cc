// MarkerResidual: GradientChecker on RightQuaternionManifold, and an autodiff twin
// (the same residual templated on ceres::Jet through DynamicAutoDiffCostFunction).
#include "problems/marker_solve/marker_residual.h"

#include <algorithm>
#include <memory>
#include <random>

#include <ceres/dynamic_autodiff_cost_function.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include "kinematics/rotation.h"
#include "solvers/right_quaternion_manifold.h"
#include "tests/kinematics/test_rigs.h"

namespace mocapsolve {
namespace {

// The twin: FK along the chain on normalized quaternions, templated.
struct MarkerResidualTwin {
  const Skeleton* skeleton;
  const MarkerSet* markers;
  int marker;
  Eigen::Vector3d observed;
  double weight;

  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    const std::vector<int>& chain = markers->InfluencingJoints(marker);
    std::vector<Eigen::Quaternion<T>> rotation(skeleton->num_joints());
    std::vector<Eigen::Matrix<T, 3, 1>> position(skeleton->num_joints());
    for (size_t s = 0; s < chain.size(); ++s) {
      const int j = chain[s];
      const T* p = parameters[1 + s];
      const T norm = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
      const Eigen::Quaternion<T> local = skeleton->rest_rotation(j).cast<T>() *
                                         Eigen::Quaternion<T>(p[3] / norm, p[0] / norm, p[1] / norm, p[2] / norm);
      if (j == 0) {
        position[0] = Eigen::Matrix<T, 3, 1>(parameters[0][0], parameters[0][1], parameters[0][2]);
        rotation[0] = local;
      } else {
        const int parent = skeleton->parent(j);
        position[j] = position[parent] + rotation[parent] * skeleton->offset(j).cast<T>();
        rotation[j] = rotation[parent] * local;
      }
    }
    Eigen::Matrix<T, 3, 1> x = Eigen::Matrix<T, 3, 1>::Zero();
    for (const MarkerAttachment& a : markers->marker(marker).attachments) {
      x += T(a.weight) * (position[a.joint] + rotation[a.joint] * a.offset.cast<T>());
    }
    for (int i = 0; i < 3; ++i) residuals[i] = T(weight) * (x[i] - T(observed[i]));
    return true;
  }
};

MarkerSet MakeMarkers(const Skeleton& skeleton) {
  std::vector<MarkerSpec> specs = {
      {"HEAD", {{4, 1.0, {0.02, 0.1, 0.03}}}},
      {"ON_JOINT", {{6, 1.0, {0.0, 0.0, 0.0}}}},  // Coincident with the joint origin.
      {"ZERO_BONE", {{3, 1.0, {0.01, 0.0, 0.05}}}},  // On the zero-length neck.
      // Generic offsets: one along a joint axis would make a column exactly zero, which
      // GradientChecker's relative error cannot judge.
      {"BLEND", {{6, 0.5, {0.05, 0.02, 0.01}}, {8, 0.3, {-0.05, 0.01, 0.03}}, {10, 0.2, {0.02, 0.01, 0.1}}}},
      {"ROOT", {{0, 1.0, {0.1, 0.0, -0.1}}}},
  };
  MarkerSet markers;
  const Status status = MarkerSet::Create(skeleton, specs, &markers);
  EXPECT_TRUE(status.ok()) << status.message();
  return markers;
}

class MarkerResidualTest : public ::testing::Test {
 protected:
  Skeleton skeleton_ = testing::MakeTestSkeleton();
  MarkerSet markers_ = MakeMarkers(skeleton_);
  Eigen::Vector3d observed_ = Eigen::Vector3d(0.3, 1.2, -0.4);
};

TEST_F(MarkerResidualTest, GradientCheckerOnTheManifold) {
  RightQuaternionManifold quaternion_manifold;
  for (const testing::NamedPose& sample : testing::ResidualPoseSweep(skeleton_, 17)) {
    for (int m = 0; m < markers_.num_markers(); ++m) {
      MarkerResidual residual(&skeleton_, &markers_, m, &observed_, 2.0);
      std::vector<const double*> parameters = {sample.pose.translations[0].data()};
      std::vector<const ceres::Manifold*> manifolds = {nullptr};
      for (int j : residual.joints()) {
        parameters.push_back(sample.pose.rotations[j].coeffs().data());
        manifolds.push_back(&quaternion_manifold);
      }
      ceres::NumericDiffOptions options;
      ceres::GradientChecker checker(&residual, &manifolds, options);
      ceres::GradientChecker::ProbeResults results;
      checker.Probe(parameters.data(), 1e-7, &results);
      ASSERT_TRUE(results.return_value);
      // Probe's verdict is purely relative and flags entries that are zero up to
      // round-off (1e-17 against 1e-15); judge the tangent-space Jacobians it computed with
      // a mixed tolerance instead: central differences are good to ~1e-8 on O(1) values.
      for (size_t b = 0; b < results.local_jacobians.size(); ++b) {
        const ceres::Matrix& analytic = results.local_jacobians[b];
        const ceres::Matrix& numeric = results.local_numeric_jacobians[b];
        const double error = (analytic - numeric).cwiseAbs().maxCoeff();
        EXPECT_LT(error, 1e-7 * std::max(1.0, numeric.cwiseAbs().maxCoeff()))
            << sample.name << " marker " << markers_.label(m) << " block " << b << "\n"
            << results.error_log;
      }
    }
  }
}

TEST_F(MarkerResidualTest, MatchesAutodiffTwin) {
  for (const testing::NamedPose& sample : testing::ResidualPoseSweep(skeleton_, 17)) {
    for (int m = 0; m < markers_.num_markers(); ++m) {
      MarkerResidual residual(&skeleton_, &markers_, m, &observed_, 2.0);
      auto* twin_functor = new MarkerResidualTwin{&skeleton_, &markers_, m, observed_, 2.0};
      ceres::DynamicAutoDiffCostFunction<MarkerResidualTwin, 4> twin(twin_functor);
      twin.AddParameterBlock(3);
      std::vector<const double*> parameters = {sample.pose.translations[0].data()};
      for (int j : residual.joints()) {
        twin.AddParameterBlock(4);
        parameters.push_back(sample.pose.rotations[j].coeffs().data());
      }
      twin.SetNumResiduals(3);
      const int blocks = static_cast<int>(parameters.size());
      std::vector<std::vector<double>> jac(blocks), twin_jac(blocks);
      std::vector<double*> jac_ptr(blocks), twin_jac_ptr(blocks);
      for (int b = 0; b < blocks; ++b) {
        const int size = b == 0 ? 3 : 4;
        jac[b].assign(3 * size, 0.0);
        twin_jac[b].assign(3 * size, 0.0);
        jac_ptr[b] = jac[b].data();
        twin_jac_ptr[b] = twin_jac[b].data();
      }
      double r[3], twin_r[3];
      ASSERT_TRUE(residual.Evaluate(parameters.data(), r, jac_ptr.data()));
      ASSERT_TRUE(twin.Evaluate(parameters.data(), twin_r, twin_jac_ptr.data()));
      for (int i = 0; i < 3; ++i) {
        // Same arithmetic in a different order: residuals agree to round-off.
        EXPECT_NEAR(r[i], twin_r[i], 1e-12) << sample.name;
      }
      for (int b = 0; b < blocks; ++b) {
        for (size_t k = 0; k < jac[b].size(); ++k) {
          // Both are exact derivatives; only round-off separates them.
          EXPECT_NEAR(jac[b][k], twin_jac[b][k], 1e-10)
              << sample.name << " marker " << markers_.label(m) << " block " << b << " entry " << k;
        }
      }
    }
  }
}

TEST_F(MarkerResidualTest, ResidualIsWeightedPredictionMinusObservation) {
  std::mt19937 rng(3);
  Pose pose = testing::RandomPose(skeleton_, &rng);
  // The solve keeps non-root joints at their skeleton offsets.
  pose.translations[9] = skeleton_.offset(9);
  FkData fk(skeleton_);
  ForwardKinematics(skeleton_, pose, &fk);
  for (int m = 0; m < markers_.num_markers(); ++m) {
    MarkerResidual residual(&skeleton_, &markers_, m, &observed_, 3.0);
    std::vector<const double*> parameters = {pose.translations[0].data()};
    for (int j : residual.joints()) parameters.push_back(pose.rotations[j].coeffs().data());
    double r[3];
    ASSERT_TRUE(residual.Evaluate(parameters.data(), r, nullptr));
    const Eigen::Vector3d expected = 3.0 * (markers_.Position(m, fk) - observed_);
    EXPECT_LT((Eigen::Map<Eigen::Vector3d>(r) - expected).norm(), 1e-13);
  }
}

}  // namespace
}  // namespace mocapsolve
