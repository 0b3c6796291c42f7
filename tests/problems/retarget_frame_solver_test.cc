// RetargetFrameSolver: the lean DLS kernel linearizes exactly as the kinematics layer
// (and so as TrackedVertexResidual, tested against it), takes the same steps as the
// generic DlsSolver on the residual blocks, and Ceres reaches the same cost.
#include "problems/retarget/retarget_frame_solver.h"

#include <random>

#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/kinematic_jacobians.h"
#include "kinematics/rotation.h"
#include "kinematics/skinning.h"
#include "tests/kinematics/test_rigs.h"

namespace mocapsolve {
namespace {

class RetargetFrameSolverTest : public ::testing::Test {
 protected:
  RetargetFrameSolverTest() : rng_(11), skeleton_(testing::MakeTestSkeleton()),
                              mesh_(testing::MakeTestMesh(skeleton_, &rng_)) {
    // Every vertex tracked, alternating positions and normals.
    for (int v = 0; v < mesh_.num_vertices(); ++v) {
      TrackedVertex t;
      t.source_vertex = t.target_vertex = v;
      t.track_position = v % 3 != 1;
      setup_.tracked.push_back(t);
    }
    // Goals: the mesh at a hidden random pose (non-root translations at their offsets).
    truth_ = Sanitize(testing::RandomPose(skeleton_, &rng_, 0.5));
    Goals(truth_, &goal_positions_, &goal_normals_);
  }

  Pose Sanitize(Pose pose) const {
    const Pose rest = RestPose(skeleton_);
    for (int j = 1; j < skeleton_.num_joints(); ++j) pose.translations[j] = rest.translations[j];
    return pose;
  }

  void Goals(const Pose& pose, Eigen::Matrix3Xd* positions, Eigen::Matrix3Xd* normals) const {
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, pose, &fk);
    std::vector<Eigen::Isometry3d> transforms;
    ComputeSkinningTransforms(mesh_, fk, &transforms);
    SkinMesh(mesh_, transforms, positions, normals);
  }

  // A warm start near the truth.
  Pose Start() {
    Pose start = truth_;
    std::normal_distribution<double> normal;
    for (auto& q : start.rotations) q = q * ExpMap(0.2 * Eigen::Vector3d(normal(rng_), normal(rng_), normal(rng_)));
    start.translations[0] += 0.05 * Eigen::Vector3d(normal(rng_), normal(rng_), normal(rng_));
    return start;
  }

  std::mt19937 rng_;
  Skeleton skeleton_;
  SkinnedMesh mesh_;
  RetargetSetup setup_;
  Pose truth_;
  Eigen::Matrix3Xd goal_positions_, goal_normals_;
  const double sigma_ = 0.4;
};

TEST_F(RetargetFrameSolverTest, LeanLinearizationEqualsKinematicJacobians) {
  RetargetSolveOptions options;
  options.normal_weight = 0.7;
  RetargetFrameSolver solver(skeleton_, mesh_, setup_, sigma_, options);
  for (int trial = 0; trial < 3; ++trial) {
    const Pose pose = Sanitize(testing::RandomPose(skeleton_, &rng_));
    Eigen::VectorXd residual;
    Eigen::MatrixXd jacobian;
    solver.Linearize(goal_positions_, goal_normals_, pose, &residual, &jacobian);
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, pose, &fk);
    std::vector<Eigen::Isometry3d> transforms;
    ComputeSkinningTransforms(mesh_, fk, &transforms);
    for (size_t s = 0; s < setup_.tracked.size(); ++s) {
      const int v = setup_.tracked[s].target_vertex;
      const bool position = setup_.tracked[s].track_position;
      const double scale = position ? 1.0 / sigma_ : 0.7;
      PoseJacobian reference;
      Eigen::Vector3d r;
      if (position) {
        SkinnedPositionJacobian(skeleton_, mesh_, fk, transforms, v, &reference);
        r = scale * (SkinPosition(mesh_, transforms, v) - goal_positions_.col(s));
      } else {
        SkinnedNormalJacobian(skeleton_, mesh_, fk, transforms, v, &reference);
        r = scale * (SkinNormal(mesh_, transforms, v) - goal_normals_.col(s));
      }
      // Exact formulas on both sides: round-off only.
      EXPECT_LT((residual.segment<3>(3 * s) - r).norm(), 1e-12) << "vertex " << v;
      EXPECT_LT((jacobian.middleRows<3>(3 * s) - scale * reference).cwiseAbs().maxCoeff(), 1e-11)
          << "vertex " << v;
    }
  }
}

// Both forms of the lean kernel: the block-sparse normal equations (40 tracked vertices,
// 120 rows >= 36 columns) and eq. 18's J^T (J J^T + lambda I)^-1 (4 vertices, 12 rows),
// with and without the smoothness rows.
TEST_F(RetargetFrameSolverTest, LeanAndGenericDlsTakeTheSameSteps) {
  RetargetSetup few = setup_;
  few.tracked.resize(4);
  for (const RetargetSetup* setup : {&setup_, &few}) {
    const int nt = static_cast<int>(setup->tracked.size());
    const Eigen::Matrix3Xd positions = goal_positions_.leftCols(nt), normals = goal_normals_.leftCols(nt);
    for (double smoothness : {0.0, 0.3}) {
      SCOPED_TRACE(::testing::Message() << nt << " tracked vertices, smoothness " << smoothness);
      RetargetSolveOptions options;
      options.iterations = 4;
      options.smoothness_weight = smoothness;
      options.solver = SolverKind::kDls;
      RetargetFrameSolver lean(skeleton_, mesh_, *setup, sigma_, options);
      options.solver = SolverKind::kDlsGeneric;
      RetargetFrameSolver generic(skeleton_, mesh_, *setup, sigma_, options);
      const Pose start = Start();
      Pose a = start, b = start;
      RetargetFrameReport ra, rb;
      ASSERT_TRUE(lean.Solve(positions, normals, &a, &ra).ok());
      ASSERT_TRUE(generic.Solve(positions, normals, &b, &rb).ok());
      EXPECT_EQ(ra.iterations, 4);
      EXPECT_EQ(rb.iterations, 4);
      // Same linear algebra in a different order: agreement to round-off.
      EXPECT_NEAR(ra.initial_cost, rb.initial_cost, 1e-10 * (1.0 + rb.initial_cost));
      EXPECT_NEAR(ra.final_cost, rb.final_cost, 1e-9 * (1.0 + rb.final_cost));
      EXPECT_LT(ra.final_cost, ra.initial_cost);
      EXPECT_LT((a.translations[0] - b.translations[0]).norm(), 1e-9);
      for (int j = 0; j < skeleton_.num_joints(); ++j) {
        EXPECT_LT(AngularDistance(a.rotations[j], b.rotations[j]), 1e-8) << "joint " << j;
      }
    }
  }
}

// Soft joint limits (JointLimitResidual rows) through both DLS paths: same steps, and the
// limited joints end nearer their limits than without.
TEST_F(RetargetFrameSolverTest, JointLimitsTakeTheSameStepsInBothDlsPaths) {
  std::vector<JointSpec> joints;
  for (int j = 0; j < skeleton_.num_joints(); ++j) {
    joints.push_back(skeleton_.joint(j));
    joints.back().rotation_limits.clear();
  }
  for (int j : {5, 9}) joints[j].rotation_limits = {{-0.1, 0.1}, {-0.1, 0.1}, {-0.1, 0.1}};
  Skeleton limited;
  ASSERT_TRUE(Skeleton::Create(joints, skeleton_.end_sites(), skeleton_.unit(), &limited).ok());
  RetargetSolveOptions options;
  options.iterations = 4;
  options.limit_weight = 2.0;
  options.solver = SolverKind::kDls;
  RetargetFrameSolver lean(limited, mesh_, setup_, sigma_, options);
  options.solver = SolverKind::kDlsGeneric;
  RetargetFrameSolver generic(limited, mesh_, setup_, sigma_, options);
  const Pose start = Start();
  Pose a = start, b = start;
  RetargetFrameReport ra, rb;
  ASSERT_TRUE(lean.Solve(goal_positions_, goal_normals_, &a, &ra).ok());
  ASSERT_TRUE(generic.Solve(goal_positions_, goal_normals_, &b, &rb).ok());
  // Same linear algebra in a different order: agreement to round-off.
  EXPECT_NEAR(ra.final_cost, rb.final_cost, 1e-9 * (1.0 + rb.final_cost));
  for (int j = 0; j < limited.num_joints(); ++j) {
    EXPECT_LT(AngularDistance(a.rotations[j], b.rotations[j]), 1e-8) << "joint " << j;
  }
  options.solver = SolverKind::kDls;
  options.limit_weight = 0.0;
  RetargetFrameSolver free(limited, mesh_, setup_, sigma_, options);
  Pose c = start;
  ASSERT_TRUE(free.Solve(goal_positions_, goal_normals_, &c, nullptr).ok());
  for (int j : {5, 9}) {
    EXPECT_LT(AngularDistance(a.rotations[j], Eigen::Quaterniond::Identity()),
              AngularDistance(c.rotations[j], Eigen::Quaterniond::Identity()))
        << "joint " << j;
  }
}

TEST_F(RetargetFrameSolverTest, DlsAndCeresRecoverTheHiddenPose) {
  for (SolverKind kind : {SolverKind::kDls, SolverKind::kCeres}) {
    RetargetSolveOptions options;
    options.solver = kind;
    options.iterations = 30;
    options.lambda = 1e-3;  // Near Gauss-Newton, so that 30 iterations reach round-off.
    options.ceres = DefaultRetargetCeresOptions();
    RetargetFrameSolver solver(skeleton_, mesh_, setup_, sigma_, options);
    Pose pose = Start();
    RetargetFrameReport report;
    ASSERT_TRUE(solver.Solve(goal_positions_, goal_normals_, &pose, &report).ok());
    // A zero-residual problem solved to convergence: vertex error ~ round-off.
    EXPECT_LT(report.mean_position_error, 1e-6) << SolverKindName(kind);
    EXPECT_LT(report.mean_normal_angle, 1e-6) << SolverKindName(kind);
    EXPECT_LT(report.final_cost, 1e-12) << SolverKindName(kind);
  }
}

TEST_F(RetargetFrameSolverTest, RejectsGoalsOfTheWrongSize) {
  RetargetFrameSolver solver(skeleton_, mesh_, setup_, sigma_, RetargetSolveOptions());
  Pose pose = Start();
  const Eigen::Matrix3Xd few(3, 2);
  EXPECT_FALSE(solver.Solve(few, few, &pose, nullptr).ok());
}

TEST(RetargetSolveOptionsTest, Validation) {
  std::string error;
  RetargetSolveOptions options;
  EXPECT_TRUE(options.IsValid(&error));
  options.iterations = 0;
  EXPECT_FALSE(options.IsValid(&error));
  options.iterations = 5;
  options.lambda = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
  SolverKind kind;
  EXPECT_TRUE(ParseSolverKind("ceres", &kind));
  EXPECT_EQ(kind, SolverKind::kCeres);
  EXPECT_FALSE(ParseSolverKind("lm", &kind));
}

}  // namespace
}  // namespace mocapsolve
