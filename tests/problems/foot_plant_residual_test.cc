// FootPlantResidual: GradientChecker on RightQuaternionManifold, an autodiff twin, and
// the kinematics layer's JointPositionJacobian, over the pose sweep (zero, random, near
// pi, gimbal); then the plant rows of the lean DLS kernel (RetargetFrameSolver::Linearize)
// against the same, both DLS paths taking the same steps with plants on, and a planted
// joint held at its anchor by the lean kernel and by Ceres.
#include "problems/retarget/foot_plant_residual.h"

#include <algorithm>
#include <random>

#include <ceres/dynamic_autodiff_cost_function.h>
#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/kinematic_jacobians.h"
#include "kinematics/rotation.h"
#include "kinematics/skinning.h"
#include "problems/retarget/retarget_frame_solver.h"
#include "solvers/right_quaternion_manifold.h"
#include "tests/kinematics/test_rigs.h"
#include "tests/problems/chain_fk_twin.h"
#include "tests/problems/manifold_gradient_check.h"

namespace mocapsolve {
namespace {

struct FootPlantTwin {
  const Skeleton* skeleton;
  Eigen::Vector3d anchor;
  double scale;
  std::vector<int> chain;

  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    const Eigen::Matrix<T, 3, 1> end = testing::ChainEndPosition(*skeleton, chain, parameters);
    for (int i = 0; i < 3; ++i) residuals[i] = T(scale) * (end[i] - T(anchor[i]));
    return true;
  }
};

class FootPlantResidualTest : public ::testing::Test {
 protected:
  FootPlantResidualTest() : skeleton_(testing::MakeTestSkeleton()) {}
  std::vector<int> Joints() const { return {0, skeleton_.num_joints() / 2, skeleton_.num_joints() - 1}; }
  Skeleton skeleton_;
  Eigen::Vector3d anchor_ = Eigen::Vector3d(0.3, -0.2, 0.8);
  double scale_ = 3.5;
};

TEST_F(FootPlantResidualTest, GradientCheckerOnTheManifold) {
  for (const testing::NamedPose& sample : testing::ResidualPoseSweep(skeleton_, 31)) {
    for (int k : Joints()) {
      FootPlantResidual residual(&skeleton_, k, &anchor_, &scale_);
      testing::ExpectJacobianMatchesNumericOnManifold(residual, residual.joints(), sample.pose,
                                                      sample.name + " joint " + std::to_string(k));
    }
  }
}

TEST_F(FootPlantResidualTest, MatchesAutodiffTwinAndKinematicJacobians) {
  for (const testing::NamedPose& sample : testing::ResidualPoseSweep(skeleton_, 31)) {
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, sample.pose, &fk);
    for (int k : Joints()) {
      FootPlantResidual residual(&skeleton_, k, &anchor_, &scale_);
      ceres::DynamicAutoDiffCostFunction<FootPlantTwin, 4> twin(
          new FootPlantTwin{&skeleton_, anchor_, scale_, residual.joints()});
      twin.AddParameterBlock(3);
      std::vector<const double*> parameters = {sample.pose.translations[0].data()};
      for (int j : residual.joints()) {
        twin.AddParameterBlock(4);
        parameters.push_back(sample.pose.rotations[j].coeffs().data());
      }
      twin.SetNumResiduals(3);
      const size_t nb = parameters.size();
      std::vector<std::vector<double>> ja(nb), jt(nb);
      std::vector<double*> pa(nb), pt(nb);
      for (size_t b = 0; b < nb; ++b) {
        ja[b].assign(b == 0 ? 9 : 12, 0.0);
        jt[b].assign(b == 0 ? 9 : 12, 0.0);
        pa[b] = ja[b].data();
        pt[b] = jt[b].data();
      }
      double ra[3], rt[3];
      ASSERT_TRUE(residual.Evaluate(parameters.data(), ra, pa.data()));
      ASSERT_TRUE(twin.Evaluate(parameters.data(), rt, pt.data()));
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(ra[i], rt[i], 1e-9) << sample.name;
        EXPECT_NEAR(ra[i], scale_ * (fk.world_positions[k][i] - anchor_[i]), 1e-9) << sample.name;
      }
      for (size_t b = 0; b < nb; ++b) {
        for (size_t i = 0; i < ja[b].size(); ++i) {
          EXPECT_NEAR(ja[b][i], jt[b][i], 1e-10 * std::max(1.0, std::abs(jt[b][i])))
              << sample.name << " joint " << k << " block " << b << " entry " << i;
        }
      }
      // Tangent blocks against the kinematics layer.
      PoseJacobian reference;
      reference.setZero(3, 3 + 3 * skeleton_.num_joints());
      JointPositionJacobian(skeleton_, fk, k, &reference);
      EXPECT_LT((Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(ja[0].data()) -
                 scale_ * reference.leftCols<3>()).cwiseAbs().maxCoeff(), 1e-12);
      for (size_t s = 0; s < residual.joints().size(); ++s) {
        const int j = residual.joints()[s];
        const Eigen::Matrix3d tangent = Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>>(ja[1 + s].data()) *
                                        QuaternionPlusJacobian(parameters[1 + s]);
        EXPECT_LT((tangent - scale_ * reference.middleCols<3>(3 + 3 * j)).cwiseAbs().maxCoeff(), 1e-10)
            << sample.name << " joint " << k << " chain joint " << j;
      }
      double rn[3];
      ASSERT_TRUE(residual.Evaluate(parameters.data(), rn, nullptr));
      EXPECT_EQ(rn[0], ra[0]);
    }
  }
}

// The plants in RetargetFrameSolver: a few tracked vertices plus two planted joints.
class FootPlantSolveTest : public ::testing::Test {
 protected:
  FootPlantSolveTest() : rng_(17), skeleton_(testing::MakeTestSkeleton()),
                         mesh_(testing::MakeTestMesh(skeleton_, &rng_)) {
    for (int v = 0; v < mesh_.num_vertices(); ++v) {
      TrackedVertex t;
      t.source_vertex = t.target_vertex = v;
      t.track_position = v % 3 != 1;
      setup_.tracked.push_back(t);
    }
    Pose truth = Sanitize(testing::RandomPose(skeleton_, &rng_, 0.5));
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, truth, &fk);
    std::vector<Eigen::Isometry3d> transforms;
    ComputeSkinningTransforms(mesh_, fk, &transforms);
    SkinMesh(mesh_, transforms, &goal_positions_, &goal_normals_);
    plants_ = {skeleton_.num_joints() - 1, skeleton_.num_joints() / 2};
    anchors_.resize(3, 2);
    for (int p = 0; p < 2; ++p) anchors_.col(p) = fk.world_positions[plants_[p]] + Eigen::Vector3d(0.1, -0.05, 0.08);
  }
  Pose Sanitize(Pose pose) const {
    const Pose rest = RestPose(skeleton_);
    for (int j = 1; j < skeleton_.num_joints(); ++j) pose.translations[j] = rest.translations[j];
    return pose;
  }
  RetargetSolveOptions Options(SolverKind kind) const {
    RetargetSolveOptions options;
    options.solver = kind;
    options.iterations = 4;
    options.plant_joints = plants_;
    options.plant_weight = 5.0;
    options.ceres = DefaultRetargetCeresOptions();
    return options;
  }
  std::mt19937 rng_;
  Skeleton skeleton_;
  SkinnedMesh mesh_;
  RetargetSetup setup_;
  Eigen::Matrix3Xd goal_positions_, goal_normals_, anchors_;
  std::vector<int> plants_;
  const double sigma_ = 0.4;
};

TEST_F(FootPlantSolveTest, LeanKernelRowsEqualTheJointJacobian) {
  RetargetFrameSolver solver(skeleton_, mesh_, setup_, sigma_, Options(SolverKind::kDls));
  const int nt = static_cast<int>(setup_.tracked.size());
  for (const testing::NamedPose& sample : testing::ResidualPoseSweep(skeleton_, 7)) {
    for (const std::vector<char>& active : {std::vector<char>{1, 1}, std::vector<char>{0, 1}}) {
      solver.SetPlants(anchors_, active);
      Eigen::VectorXd residual;
      Eigen::MatrixXd jacobian;
      solver.Linearize(goal_positions_, goal_normals_, sample.pose, &residual, &jacobian);
      ASSERT_EQ(residual.size(), 3 * (nt + 2));
      FkData fk(skeleton_);
      ForwardKinematics(skeleton_, sample.pose, &fk);
      for (int p = 0; p < 2; ++p) {
        const double scale = active[p] ? 5.0 / sigma_ : 0.0;
        PoseJacobian reference;
        reference.setZero(3, 3 + 3 * skeleton_.num_joints());
        JointPositionJacobian(skeleton_, fk, plants_[p], &reference);
        const int row = 3 * (nt + p);
        EXPECT_LT((residual.segment<3>(row) - scale * (fk.world_positions[plants_[p]] - anchors_.col(p))).norm(), 1e-10)
            << sample.name;
        EXPECT_LT((jacobian.middleRows<3>(row) - scale * reference).cwiseAbs().maxCoeff(), 1e-9) << sample.name;
      }
    }
  }
}

TEST_F(FootPlantSolveTest, BothDlsPathsTakeTheSameStepsAndHoldTheFoot) {
  for (bool few : {false, true}) {  // Normal equations (m >= n) and eq. 18 (m < n).
    RetargetSetup setup = setup_;
    if (few) setup.tracked.resize(2);
    const int nt = static_cast<int>(setup.tracked.size());
    const Eigen::Matrix3Xd positions = goal_positions_.leftCols(nt), normals = goal_normals_.leftCols(nt);
    RetargetFrameSolver lean(skeleton_, mesh_, setup, sigma_, Options(SolverKind::kDls));
    RetargetFrameSolver generic(skeleton_, mesh_, setup, sigma_, Options(SolverKind::kDlsGeneric));
    const std::vector<char> on = {1, 1};
    lean.SetPlants(anchors_, on);
    generic.SetPlants(anchors_, on);
    Pose a = RestPose(skeleton_), b = a;
    RetargetFrameReport ra, rb;
    ASSERT_TRUE(lean.Solve(positions, normals, &a, &ra).ok());
    ASSERT_TRUE(generic.Solve(positions, normals, &b, &rb).ok());
    EXPECT_NEAR(ra.initial_cost, rb.initial_cost, 1e-10 * (1.0 + rb.initial_cost)) << few;
    EXPECT_NEAR(ra.final_cost, rb.final_cost, 1e-9 * (1.0 + rb.final_cost)) << few;
    for (int j = 0; j < skeleton_.num_joints(); ++j) {
      EXPECT_LT(AngularDistance(a.rotations[j], b.rotations[j]), 1e-8) << few << " joint " << j;
    }
  }
  // Planted vs not, lean kernel and Ceres: the planted joints end nearer their anchors.
  for (SolverKind kind : {SolverKind::kDls, SolverKind::kCeres}) {
    RetargetSolveOptions options = Options(kind);
    options.iterations = 20;
    RetargetFrameSolver solver(skeleton_, mesh_, setup_, sigma_, options);
    double distance[2] = {0.0, 0.0};
    for (int planted = 0; planted < 2; ++planted) {
      solver.SetPlants(anchors_, {static_cast<char>(planted), static_cast<char>(planted)});
      Pose pose = RestPose(skeleton_);
      ASSERT_TRUE(solver.Solve(goal_positions_, goal_normals_, &pose, nullptr).ok());
      FkData fk(skeleton_);
      ForwardKinematics(skeleton_, pose, &fk);
      for (int p = 0; p < 2; ++p) distance[planted] += (fk.world_positions[plants_[p]] - anchors_.col(p)).norm();
    }
    EXPECT_LT(distance[1], 0.5 * distance[0]) << SolverKindName(kind);
  }
}

}  // namespace
}  // namespace mocapsolve
