#include "problems/marker_solve/marker_clip_solver.h"

#include <random>
#include <string>
#include <utility>
#include <vector>

#include <ceres/crs_matrix.h>
#include <ceres/problem.h>
#include <gtest/gtest.h>
#include <Eigen/SparseCore>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "problems/marker_solve/sequence_solver.h"
#include "tests/problems/cmu0201_test_support.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// Mean world joint position error against the truth (cm).
double MeanJointError(const Skeleton& skeleton, const Motion& a, const Motion& b) {
  FkData fa(skeleton), fb(skeleton);
  double sum = 0.0;
  for (int f = 0; f < a.num_frames(); ++f) {
    ForwardKinematics(skeleton, a.frames[f], &fa);
    ForwardKinematics(skeleton, b.frames[f], &fb);
    for (int j = 0; j < skeleton.num_joints(); ++j) sum += (fa.world_positions[j] - fb.world_positions[j]).norm();
  }
  return sum / (a.num_frames() * skeleton.num_joints());
}

class MarkerClipSolverTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 rng(1);
    markers_ = MakeSyntheticMarkerSet(skeleton_, 3, rng());
    truth_ = MakeDemoWalk(skeleton_, 60, 60.0);
    FkData fk(skeleton_);
    for (const Pose& pose : truth_.frames) {
      ForwardKinematics(skeleton_, pose, &fk);
      clean_.emplace_back();
      for (int m = 0; m < markers_.num_markers(); ++m) clean_.back().push_back(markers_.Position(m, fk));
    }
  }
  Skeleton skeleton_ = MakeDemoSkeleton();
  MarkerSet markers_;
  Motion truth_;
  std::vector<std::vector<Eigen::Vector3d>> clean_;
};

TEST_F(MarkerClipSolverTest, NoiseFreeFromRestConverges) {
  Motion motion = truth_;
  for (Pose& pose : motion.frames) {
    pose = RestPose(skeleton_);
    pose.translations[0] = truth_.frames[0].translations[0];
  }
  ClipSolveOptions options;
  options.ceres = DefaultClipCeresOptions();
  options.rotation_smoothness = 1e-4;  // Nearly pure data term.
  options.translation_smoothness = 1e-4;
  ClipSolveReport report;
  const Status status = SolveClip(skeleton_, markers_, clean_, options, &motion, &report);
  ASSERT_TRUE(status.ok()) << status.message() << "\n" << report.full;
  // The tiny smoothness weight biases by far less than 0.01 cm.
  EXPECT_LT(MeanJointError(skeleton_, motion, truth_), 1e-2) << report.brief;
  EXPECT_LT(report.rms_marker_error, 1e-2);
}

TEST_F(MarkerClipSolverTest, SmoothnessBeatsPerFrameOnNoisyMarkers) {
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 0.5);  // 5 mm
  auto noisy = clean_;
  for (auto& frame : noisy) {
    for (auto& x : frame) x += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  }
  // Per-frame solutions: the clip's initial guess and the baseline.
  MarkerSolveOptions frame_options;
  frame_options.solver = SolverKind::kDls;
  MarkerFrameSolver frame_solver(skeleton_, markers_, frame_options);
  Motion per_frame = truth_;
  Pose pose = truth_.frames[0];
  for (int f = 0; f < truth_.num_frames(); ++f) {
    FrameSolveReport report;
    ASSERT_TRUE(frame_solver.Solve(noisy[f], &pose, &report).ok());
    per_frame.frames[f] = pose;
  }
  Motion clip = per_frame;
  ClipSolveOptions options;
  options.ceres = DefaultClipCeresOptions();
  options.rotation_smoothness = 30.0;
  options.translation_smoothness = 1.0;
  ClipSolveReport report;
  ASSERT_TRUE(SolveClip(skeleton_, markers_, noisy, options, &clip, &report).ok()) << report.brief;
  const double frame_error = MeanJointError(skeleton_, per_frame, truth_);
  const double clip_error = MeanJointError(skeleton_, clip, truth_);
  EXPECT_LT(clip_error, 0.8 * frame_error) << "per-frame " << frame_error << " cm, clip " << clip_error << " cm";
}

// The DLS path's normal equations equal those of Ceres' evaluator on the same blocks:
// J^T J and J^T r from ceres::Problem::Evaluate's tangent Jacobian (CRSMatrix), for
// velocity and acceleration smoothness, both sparse forms. With a robust loss the
// gradient and cost match (IRLS weights sqrt(rho') give Ceres' J^T rho' r); Ceres'
// Jacobian then carries its second-order correction, so J^T J is compared without one.
TEST_F(MarkerClipSolverTest, DlsNormalEquationsMatchCeresEvaluator) {
  const int frames = 4;
  std::vector<std::vector<Eigen::Vector3d>> observed(clean_.begin(), clean_.begin() + frames);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 2.0);  // 2 cm: some residuals beyond the loss' bend.
  for (auto& frame : observed) {
    for (auto& x : frame) x += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  }
  Motion initial = truth_;
  initial.frames.resize(frames);
  for (SmoothnessOrder order : {SmoothnessOrder::kVelocity, SmoothnessOrder::kAcceleration}) {
    for (const char* loss : {"none", "cauchy"}) {
      SCOPED_TRACE(std::string(order == SmoothnessOrder::kVelocity ? "velocity " : "acceleration ") + loss);
      ClipSolveOptions options;
      options.smoothness_order = order;
      options.loss = loss;
      options.rotation_smoothness = 3.0;
      options.translation_smoothness = 0.5;
      ClipProblem problem;
      ASSERT_TRUE(BuildClipProblem(skeleton_, markers_, observed, options, initial, &problem).ok());
      ceres::Problem::Options problem_options;
      problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
      problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
      problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
      ceres::Problem ceres_problem(problem_options);
      problem.AddTo(&ceres_problem);
      double ceres_cost = 0.0;
      std::vector<double> residuals;
      ceres::CRSMatrix crs;
      ASSERT_TRUE(ceres_problem.Evaluate(ceres::Problem::EvaluateOptions(), &ceres_cost, &residuals, nullptr, &crs));
      Eigen::SparseMatrix<double> j(crs.num_rows, crs.num_cols);
      std::vector<Eigen::Triplet<double>> triplets;
      for (int r = 0; r < crs.num_rows; ++r) {
        for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) triplets.emplace_back(r, crs.cols[k], crs.values[k]);
      }
      j.setFromTriplets(triplets.begin(), triplets.end());
      const Eigen::MatrixXd ceres_jtj = Eigen::MatrixXd(j.transpose() * j);
      const Eigen::VectorXd ceres_jtr = j.transpose() * Eigen::Map<const Eigen::VectorXd>(residuals.data(), residuals.size());
      ASSERT_EQ(crs.num_cols, problem.frame_columns * frames);

      for (DlsLinearSolver form : {DlsLinearSolver::kSparseLdlt, DlsLinearSolver::kBlockBanded}) {
        DlsProblem dls_problem;
        problem.AddTo(&dls_problem);
        DlsSolver solver(form, problem.frame_columns);
        Eigen::SparseMatrix<double> jtj;
        Eigen::VectorXd jtr;
        double cost = 0.0;
        ASSERT_TRUE(solver.NormalEquations(&dls_problem, &jtj, &jtr, &cost));
        // Sums of the same products in another order: round-off.
        EXPECT_NEAR(cost, ceres_cost, 1e-12 * ceres_cost);
        EXPECT_LT((jtr - ceres_jtr).norm(), 1e-10 * ceres_jtr.norm());
        if (std::string(loss) == "none") {
          EXPECT_LT((Eigen::MatrixXd(jtj) - ceres_jtj).norm(), 1e-10 * ceres_jtj.norm());
        }
      }
    }
  }
}

// Ceres and the DLS path (the given sparse forms) reach the same final cost from the same
// per-frame initial guess; both stop at a relative cost change below function_tolerance.
void ExpectSameMinimum(const Skeleton& skeleton, const MarkerSet& markers,
                       const std::vector<std::vector<Eigen::Vector3d>>& observed, const Motion& initial,
                       ClipSolveOptions options, const std::vector<DlsLinearSolver>& forms,
                       double function_tolerance, double relative_tolerance) {
  options.ceres = DefaultClipCeresOptions();
  options.ceres.function_tolerance = function_tolerance;
  options.ceres.max_num_iterations = 300;
  options.dls = DefaultClipDlsOptions();
  options.dls.function_tolerance = function_tolerance;
  options.dls.max_iterations = 300;
  options.solver = "ceres";
  Motion ceres_motion = initial;
  ClipSolveReport ceres_report;
  ASSERT_TRUE(SolveClip(skeleton, markers, observed, options, &ceres_motion, &ceres_report).ok()) << ceres_report.brief;
  options.solver = "dls";
  for (DlsLinearSolver form : forms) {
    options.dls_linear_solver = form;
    Motion dls_motion = initial;
    ClipSolveReport dls_report;
    ASSERT_TRUE(SolveClip(skeleton, markers, observed, options, &dls_motion, &dls_report).ok()) << dls_report.brief;
    EXPECT_NEAR(dls_report.initial_cost, ceres_report.initial_cost, 1e-12 * ceres_report.initial_cost);
    EXPECT_NEAR(dls_report.final_cost, ceres_report.final_cost, relative_tolerance * ceres_report.final_cost)
        << "ceres: " << ceres_report.brief << "\ndls: " << dls_report.brief;
    EXPECT_LT(dls_report.final_cost, dls_report.initial_cost);
  }
}

TEST_F(MarkerClipSolverTest, DlsReachesCeresCostOnASyntheticClip) {
  std::mt19937 rng(4);
  std::normal_distribution<double> noise(0.0, 0.5);  // 5 mm
  std::vector<std::vector<Eigen::Vector3d>> noisy(clean_.begin(), clean_.begin() + 30);
  for (auto& frame : noisy) {
    for (auto& x : frame) x += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  }
  noisy[10][3] += Eigen::Vector3d(6.0, 0.0, 0.0);  // An outlier for the robust loss.
  MarkerSolveOptions frame_options;
  frame_options.solver = SolverKind::kDls;
  Motion initial;
  SequenceSolveReport sequence;
  ASSERT_TRUE(SolveSequence(skeleton_, markers_, noisy, frame_options, truth_.frames[0], &initial, &sequence).ok());
  initial.frame_rate = truth_.frame_rate;
  const std::vector<std::pair<SmoothnessOrder, const char*>> cases = {
      {SmoothnessOrder::kVelocity, "none"}, {SmoothnessOrder::kVelocity, "huber"},
      {SmoothnessOrder::kAcceleration, "none"}, {SmoothnessOrder::kAcceleration, "cauchy"}};
  for (const auto& [order, loss] : cases) {
    SCOPED_TRACE(std::string(order == SmoothnessOrder::kVelocity ? "velocity " : "acceleration ") + loss);
    ClipSolveOptions options;
    options.smoothness_order = order;
    options.loss = loss;
    options.rotation_smoothness = 30.0;
    // Both converge to a 1e-12 relative change: the same minimum to ~1e-9 (1e-7 allowed).
    ExpectSameMinimum(skeleton_, markers_, noisy, initial, options,
                      {DlsLinearSolver::kBlockBanded, DlsLinearSolver::kSparseLdlt}, 1e-12, 1e-7);
  }
}

// The first 60 frames of CMU 02_01's real markers (ASF dofs: 1-3 per joint).
TEST(MarkerClipSolverCmu, DlsReachesCeresCostOn0201) {
  MOCAPSOLVE_DATA_FILE(c3d, "c3d/02_01.c3d");
  MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
  MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
  testing::Cmu0201 data;
  ASSERT_TRUE(testing::LoadCmu0201(c3d, asf, amc, &data).ok());
  data.observed.resize(60);
  const MarkerSet& markers = data.calibration.marker_set;
  MarkerSolveOptions frame_options;
  frame_options.solver = SolverKind::kDls;
  frame_options.prior_rotation_weight = 20.0 / data.mm;
  Motion initial;
  SequenceSolveReport sequence;
  ASSERT_TRUE(SolveSequence(data.skeleton, markers, data.observed, frame_options, RestPose(data.skeleton),
                            &initial, &sequence).ok());
  const std::vector<std::pair<SmoothnessOrder, const char*>> cases = {
      {SmoothnessOrder::kVelocity, "none"}, {SmoothnessOrder::kAcceleration, "cauchy"}};
  for (const auto& [order, loss] : cases) {
    SCOPED_TRACE(std::string(order == SmoothnessOrder::kVelocity ? "velocity " : "acceleration ") + loss);
    ClipSolveOptions options;
    options.smoothness_order = order;
    options.loss = loss;
    options.loss_scale = 10.0 / data.mm;  // 1 cm.
    options.translation_smoothness = 0.1;
    // Redundant ASF chains make the tail slow (40-180 iterations to a 1e-12 change);
    // stopped at 1e-10, both are within ~1e-8 of the minimum (1e-6 allowed).
    ExpectSameMinimum(data.skeleton, markers, data.observed, initial, options, {DlsLinearSolver::kBlockBanded},
                      1e-10, 1e-6);
  }
}

}  // namespace
}  // namespace mocapsolve
