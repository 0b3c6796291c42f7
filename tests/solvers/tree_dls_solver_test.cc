// TreeDlsSolver: its linearization equals central differences on the manifold; its step
// (moments summed up the tree, world-frame blocks, padded ASF blocks, block-sparse
// Cholesky) equals a dense solve of the normal equations built from that linearization;
// a pure tree factors with no fill; and it reaches the generic DlsSolver's minimum.
#include "solvers/tree_dls_solver.h"

#include <random>

#include <ceres/loss_function.h>
#include <gtest/gtest.h>

#include "kinematics/rotation.h"
#include "problems/marker_solve/pose_prior_residual.h"
#include "solvers/right_quaternion_manifold.h"
#include "tests/kinematics/test_rigs.h"

namespace mocapsolve {
namespace {

class TreeDlsSolverTest : public ::testing::Test {
 protected:
  TreeDlsSolverTest() : rng_(5), skeleton_(testing::MakeTestSkeleton()) {
    const int nj = skeleton_.num_joints();
    rotations_.assign(4 * nj, 0.0);
    reference_.assign(4 * nj, 0.0);
    std::normal_distribution<double> normal;
    for (int j = 0; j < nj; ++j) {
      const Eigen::Quaterniond q = ExpMap(0.3 * Eigen::Vector3d(normal(rng_), normal(rng_), normal(rng_)));
      Eigen::Map<Eigen::Vector4d> reference(&reference_[4 * j]);
      reference = q.coeffs();
    }
    SetPose(0.4);
    goals_.resize(12);
    for (auto& g : goals_) g = 10.0 * Eigen::Vector3d(normal(rng_), normal(rng_), normal(rng_));
  }

  void SetPose(double angle) {
    std::normal_distribution<double> normal;
    for (int j = 0; j < skeleton_.num_joints(); ++j) {
      const Eigen::Quaterniond q = ExpMap(angle * Eigen::Vector3d(normal(rng_), normal(rng_), normal(rng_)));
      Eigen::Map<Eigen::Vector4d> rotation(&rotations_[4 * j]);
      rotation = q.coeffs();
    }
    translation_ = Eigen::Vector3d(1.0, -2.0, 0.5);
  }

  Eigen::Vector3d Local() {
    std::normal_distribution<double> normal;
    return 5.0 * Eigen::Vector3d(normal(rng_), normal(rng_), normal(rng_));
  }

  // Joints: free (RightQuaternionManifold) except 2 (one dof, an ASF hinge), 6 (two dofs)
  // and 3 (held). Rows: single-bone points, points blended over bones of different
  // branches, a blended direction; priors on joints 1 and 6 and on the translation.
  void Build(TreeDlsSolver* solver, double translation_scale) {
    for (int j = 0; j < skeleton_.num_joints(); ++j) {
      if (j == 3) continue;
      solver->SetJointManifold(j, j == 2 ? RotationManifold({0}) : j == 6 ? RotationManifold({2, 0}) : &full_);
    }
    solver->set_translation_scale(translation_scale);
    solver->AddPointRow({{4, 1.0, Local()}}, &goals_[0], 1.0);
    solver->AddPointRow({{6, 1.0, Local()}}, &goals_[1], 0.7);
    solver->AddPointRow({{10, 1.0, Local()}}, &goals_[2], 1.3);
    solver->AddPointRow({{8, 0.5, Local()}, {6, 0.3, Local()}, {2, 0.2, Local()}}, &goals_[3], 1.0);
    solver->AddPointRow({{10, 0.6, Local()}, {4, 0.4, Local()}}, &goals_[4], 0.9);
    solver->AddPointRow({{5, 1.0, Local()}}, &goals_[5], 1.0);
    solver->AddDirectionRow({{6, 0.5, Local()}, {8, 0.5, Local()}}, &goals_[6], 0.8);
    solver->AddDirectionRow({{4, 1.0, Local()}}, &goals_[7], 0.5);
    solver->AddPointRow({{0, 1.0, Local()}}, &goals_[8], 1.0);
    solver->AddPointRow({{3, 1.0, Local()}}, &goals_[9], 1.0);
    for (int j : {1, 6}) {
      priors_.emplace_back(new RotationPriorResidual(&reference_[4 * j], 2.0));
      solver->AddBlockCost(j, priors_.back().get());
    }
    translation_prior_.reset(new TranslationPriorResidual(reference_translation_, 0.3));
    solver->AddBlockCost(-1, translation_prior_.get());
  }

  std::mt19937 rng_;
  Skeleton skeleton_;
  Eigen::Vector3d translation_;
  std::vector<double> rotations_, reference_;
  double reference_translation_[3] = {0.5, -1.0, 0.0};
  std::vector<Eigen::Vector3d> goals_;
  RightQuaternionManifold full_;
  std::vector<std::unique_ptr<RotationPriorResidual>> priors_;
  std::unique_ptr<TranslationPriorResidual> translation_prior_;
};

TEST_F(TreeDlsSolverTest, LinearizationEqualsCentralDifferencesOnTheManifold) {
  TreeDlsSolver solver(&skeleton_, translation_.data(), rotations_.data());
  Build(&solver, 1.0);
  Eigen::VectorXd r0;
  Eigen::MatrixXd jacobian;
  solver.Linearize(&r0, &jacobian);
  const double h = 1e-6;
  for (int c = 0; c < jacobian.cols(); ++c) {
    const int j = (c - 3) / 3;
    if (c >= 3 && (j == 3)) continue;  // Held: its columns stay zero.
    const std::vector<double> rotations = rotations_;
    const Eigen::Vector3d translation = translation_;
    Eigen::VectorXd plus, minus;
    Eigen::MatrixXd unused;
    for (double sign : {1.0, -1.0}) {
      if (c < 3) {
        translation_[c] += sign * h;
      } else {
        Eigen::Map<Eigen::Quaterniond> q(&rotations_[4 * j]);
        q = q * ExpMap(sign * h * Eigen::Vector3d::Unit((c - 3) % 3));
      }
      solver.Linearize(sign > 0 ? &plus : &minus, &unused);
      rotations_ = rotations;
      translation_ = translation;
    }
    const Eigen::VectorXd numeric = (plus - minus) / (2.0 * h);
    // Central differences, h = 1e-6 on coordinates ~10: truncation and round-off ~1e-7.
    EXPECT_LT((numeric - jacobian.col(c)).cwiseAbs().maxCoeff(), 1e-6) << "column " << c;
  }
}

// One fixed-damping step of the kernel against (J^T J + lambda I) delta = -J^T r formed
// densely from Linearize, the manifolds' PlusJacobians and the block costs, with and
// without a robust loss, translation scale 1 and 0.4.
TEST_F(TreeDlsSolverTest, StepEqualsTheDenseNormalEquations) {
  ceres::CauchyLoss cauchy(3.0);
  for (const ceres::LossFunction* loss : {static_cast<const ceres::LossFunction*>(nullptr),
                                          static_cast<const ceres::LossFunction*>(&cauchy)}) {
    for (double tau : {1.0, 0.4}) {
      SCOPED_TRACE(::testing::Message() << (loss ? "cauchy" : "no loss") << ", tau " << tau);
      SetPose(0.5);
      TreeDlsSolver solver(&skeleton_, translation_.data(), rotations_.data());
      Build(&solver, tau);
      solver.set_loss(loss);
      // Dense reference: tangent columns in the solver's order.
      const std::vector<int> solved = {0, 1, 2, 4, 5, 6, 7, 8, 9, 10};
      std::vector<const ceres::Manifold*> manifolds;
      std::vector<int> offset;
      int n = 3;
      for (int j : solved) {
        manifolds.push_back(j == 2 ? RotationManifold({0}) : j == 6 ? RotationManifold({2, 0}) : &full_);
        offset.push_back(n);
        n += manifolds.back()->TangentSize();
      }
      Eigen::VectorXd r;
      Eigen::MatrixXd local;
      solver.Linearize(&r, &local);
      const int nr = static_cast<int>(r.size());
      Eigen::MatrixXd jt = Eigen::MatrixXd::Zero(nr + 11, n);
      Eigen::VectorXd rt = Eigen::VectorXd::Zero(nr + 11);
      for (int i = 0; i < nr / 3; ++i) {
        double factor = 1.0;
        if (loss != nullptr) {
          double rho[3];
          loss->Evaluate(r.segment<3>(3 * i).squaredNorm(), rho);
          factor = std::sqrt(rho[1]);
        }
        rt.segment<3>(3 * i) = factor * r.segment<3>(3 * i);
        jt.block<3, 3>(3 * i, 0) = factor * tau * local.block<3, 3>(3 * i, 0);
        for (size_t s = 0; s < solved.size(); ++s) {
          const int j = solved[s];
          const int k = manifolds[s]->TangentSize();
          double plus[12];
          manifolds[s]->PlusJacobian(&rotations_[4 * j], plus);
          const Eigen::Map<Eigen::Matrix<double, 4, Eigen::Dynamic, Eigen::RowMajor>> p(plus, 4, k);
          const Eigen::Matrix<double, 3, Eigen::Dynamic> basis = AmbientFromTangent(&rotations_[4 * j]) * p;
          jt.block(3 * i, offset[s], 3, k) = factor * local.block<3, 3>(3 * i, 3 + 3 * j) * basis;
        }
      }
      // Block costs: priors on joints 1 and 6 (4 rows each), the translation prior (3).
      int row = nr;
      for (int idx : {1, 5}) {  // Indices of joints 1 and 6 in `solved`.
        const int j = solved[idx];
        RotationPriorResidual prior(&reference_[4 * j], 2.0);
        const double* parameters[] = {&rotations_[4 * j]};
        double residual[4], ambient[16], plus[12];
        double* jacobians[] = {ambient};
        ASSERT_TRUE(prior.Evaluate(parameters, residual, jacobians));
        const int k = manifolds[idx]->TangentSize();
        manifolds[idx]->PlusJacobian(&rotations_[4 * j], plus);
        rt.segment<4>(row) = Eigen::Map<Eigen::Vector4d>(residual);
        jt.block(row, offset[idx], 4, k) =
            Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(ambient) *
            Eigen::Map<Eigen::Matrix<double, 4, Eigen::Dynamic, Eigen::RowMajor>>(plus, 4, k);
        row += 4;
      }
      for (int i = 0; i < 3; ++i) {
        rt[row + i] = 0.3 * (translation_[i] - reference_translation_[i]);
        jt(row + i, i) = 0.3 * tau;
      }
      const double lambda = 0.05;
      Eigen::MatrixXd a = jt.transpose() * jt;
      a.diagonal().array() += lambda;
      const Eigen::VectorXd delta = -a.ldlt().solve(jt.transpose() * rt);
      // Expected parameters after the step.
      Eigen::Vector3d expected_t = translation_ + tau * delta.head<3>();
      std::vector<double> expected_q = rotations_;
      for (size_t s = 0; s < solved.size(); ++s) {
        const int j = solved[s];
        manifolds[s]->Plus(&rotations_[4 * j], delta.data() + offset[s], &expected_q[4 * j]);
      }
      DlsOptions options;
      options.max_iterations = 1;
      options.adaptive_damping = false;
      options.lambda = lambda;
      DlsSummary summary;
      solver.Solve(options, &summary);
      ASSERT_EQ(summary.iterations, 1) << summary.BriefReport();
      // Same linear algebra in another order (moments, world frames): round-off.
      EXPECT_LT((translation_ - expected_t).norm(), 1e-9);
      for (int j = 0; j < skeleton_.num_joints(); ++j) {
        const Eigen::Quaterniond got(Eigen::Map<const Eigen::Quaterniond>(&rotations_[4 * j]));
        const Eigen::Quaterniond want(Eigen::Map<const Eigen::Quaterniond>(&expected_q[4 * j]));
        EXPECT_LT(AngularDistance(got, want), 1e-9) << "joint " << j;
      }
    }
  }
}

TEST_F(TreeDlsSolverTest, APureTreeFactorsWithoutFill) {
  TreeDlsSolver solver(&skeleton_, translation_.data(), rotations_.data());
  for (int j = 0; j < skeleton_.num_joints(); ++j) solver.SetJointManifold(j, &full_);
  for (int j = 0; j < skeleton_.num_joints(); ++j) solver.AddPointRow({{j, 1.0, Local()}}, &goals_[0], 1.0);
  // Below-diagonal blocks: per joint, its proper ancestors and the translation.
  int expected = 0;
  for (int j = 0; j < skeleton_.num_joints(); ++j) {
    for (int a = skeleton_.parent(j); a >= 0; a = skeleton_.parent(a)) ++expected;
    ++expected;
  }
  EXPECT_EQ(solver.num_factor_blocks(), expected);
}

// Adaptive damping to convergence from a distant start: the cost decreases to a minimum
// where the gradient vanishes (noisy goals, so the minimum is not zero).
TEST_F(TreeDlsSolverTest, AdaptiveDampingConverges) {
  SetPose(1.0);
  TreeDlsSolver solver(&skeleton_, translation_.data(), rotations_.data());
  Build(&solver, 1.0);
  DlsOptions options;
  options.function_tolerance = 1e-10;
  options.parameter_tolerance = 0.0;
  // The two-dof joint's second angle passes a quarter turn on the way (265 iterations to
  // 663.06; a manifold that misread poses past it stopped every step there, at 769.55).
  options.max_iterations = 400;
  DlsSummary summary;
  solver.Solve(options, &summary);
  EXPECT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
  EXPECT_LT(summary.final_cost, 700.0) << summary.BriefReport();
  EXPECT_NE(summary.termination, DlsTermination::kNoConvergence) << summary.BriefReport();
}

}  // namespace
}  // namespace mocapsolve
