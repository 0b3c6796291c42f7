// The check every joint-space residual's test makes: its analytic Jacobian over
// [root translation (3), the rotation of each joint it reads (4, RightQuaternionManifold)]
// against ceres::GradientChecker's numeric differentiation on the manifold, at one pose.
#ifndef MOCAPSOLVE_TESTS_PROBLEMS_MANIFOLD_GRADIENT_CHECK_H_
#define MOCAPSOLVE_TESTS_PROBLEMS_MANIFOLD_GRADIENT_CHECK_H_

#include <algorithm>
#include <string>
#include <vector>

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include "kinematics/skeleton.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve::testing {

// Each block's largest difference within 1e-7 of its largest numeric entry (at least 1);
// failures name `label` and the block.
inline void ExpectJacobianMatchesNumericOnManifold(const ceres::CostFunction& residual, const std::vector<int>& joints,
                                                   const Pose& pose, const std::string& label) {
  RightQuaternionManifold quaternion_manifold;
  std::vector<const double*> parameters = {pose.translations[0].data()};
  std::vector<const ceres::Manifold*> manifolds = {nullptr};
  for (int j : joints) {
    parameters.push_back(pose.rotations[j].coeffs().data());
    manifolds.push_back(&quaternion_manifold);
  }
  ceres::NumericDiffOptions options;
  ceres::GradientChecker checker(&residual, &manifolds, options);
  ceres::GradientChecker::ProbeResults results;
  checker.Probe(parameters.data(), 1e-7, &results);
  ASSERT_TRUE(results.return_value) << label;
  for (size_t b = 0; b < results.local_jacobians.size(); ++b) {
    const ceres::Matrix& analytic = results.local_jacobians[b];
    const ceres::Matrix& numeric = results.local_numeric_jacobians[b];
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-7 * std::max(1.0, numeric.cwiseAbs().maxCoeff()))
        << label << " block " << b << "\n" << results.error_log;
  }
}

}  // namespace mocapsolve::testing

#endif  // MOCAPSOLVE_TESTS_PROBLEMS_MANIFOLD_GRADIENT_CHECK_H_
