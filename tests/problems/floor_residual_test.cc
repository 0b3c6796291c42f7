// FloorResidual: GradientChecker on RightQuaternionManifold and an autodiff twin over the
// pose sweep (zero, random, near pi, gimbal), with the joint both under and above its lowest
// height (the one-sided row is zero above); then the floor in RetargetFrameSolver: the lean
// kernel's active set and the Ceres/generic DLS hinge both lift a joint that the tracked
// vertices put under the floor, and leave a solve above it unchanged.
#include "problems/retarget/floor_residual.h"

#include <algorithm>
#include <random>

#include <ceres/dynamic_autodiff_cost_function.h>
#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/skinning.h"
#include "problems/retarget/retarget_frame_solver.h"
#include "tests/kinematics/test_rigs.h"
#include "tests/problems/chain_fk_twin.h"
#include "kinematics/rotation.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

// The same residual, templated: chain FK of the joint's height, one-sided.
struct FloorTwin {
  const Skeleton* skeleton;
  double lowest;
  double scale;
  std::vector<int> chain;

  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    const T below = testing::ChainEndPosition(*skeleton, chain, parameters)[1] - T(lowest);
    residuals[0] = below < T(0.0) ? T(scale) * below : T(0.0);
    return true;
  }
};

class FloorResidualTest : public ::testing::Test {
 protected:
  FloorResidualTest() : skeleton_(testing::MakeTestSkeleton()) {}
  std::vector<int> Joints() const { return {0, skeleton_.num_joints() / 2, skeleton_.num_joints() - 1}; }
  Skeleton skeleton_;
  double scale_ = 3.5;
};

// Central differences on the manifold (q exp(+-h e_k), t +- h e_k) against the analytic
// Jacobian mapped to the tangent (ambient x PlusJacobian). ceres::GradientChecker's
// relative steps are too small on the near-zero quaternion components of these poses for a
// one-row residual (its numeric entries come out ~1e-5 off where the plant's three rows,
// with the same y row, pass), so the steps here are absolute.
void ExpectTangentJacobianMatchesCentralDifferences(const FloorResidual& residual, const Pose& pose,
                                                    const std::string& label) {
  std::vector<Eigen::Vector3d> translation = {pose.translations[0]};
  std::vector<Eigen::Vector4d> rotations;
  for (int j : residual.joints()) rotations.push_back(pose.rotations[j].coeffs());
  auto evaluate = [&](double* jacobian_out, int block, bool want) {
    std::vector<const double*> parameters = {translation[0].data()};
    for (const Eigen::Vector4d& q : rotations) parameters.push_back(q.data());
    std::vector<std::vector<double>> j(parameters.size());
    std::vector<double*> pj;
    for (size_t b = 0; b < parameters.size(); ++b) j[b].assign(b == 0 ? 3 : 4, 0.0), pj.push_back(j[b].data());
    double r = 0.0;
    EXPECT_TRUE(residual.Evaluate(parameters.data(), &r, want ? pj.data() : nullptr));
    if (want) std::copy(j[block].begin(), j[block].end(), jacobian_out);
    return r;
  };
  const double h = 1e-6;
  for (size_t b = 0; b <= rotations.size(); ++b) {
    double ambient[4] = {0, 0, 0, 0};
    evaluate(ambient, static_cast<int>(b), true);
    Eigen::RowVector3d analytic;
    if (b == 0) {
      analytic = Eigen::Map<Eigen::RowVector3d>(ambient);
    } else {
      analytic = Eigen::Map<Eigen::RowVector4d>(ambient) * QuaternionPlusJacobian(rotations[b - 1].data());
    }
    for (int k = 0; k < 3; ++k) {
      double r[2];
      for (int side = 0; side < 2; ++side) {
        const double step = side == 0 ? h : -h;
        const Eigen::Vector3d saved_t = translation[0];
        Eigen::Vector4d saved_q;
        if (b == 0) {
          translation[0][k] += step;
        } else {
          saved_q = rotations[b - 1];
          Eigen::Quaterniond q(saved_q[3], saved_q[0], saved_q[1], saved_q[2]);
          rotations[b - 1] = (q * ExpMap(step * Eigen::Vector3d::Unit(k))).coeffs();
        }
        r[side] = evaluate(nullptr, 0, false);
        translation[0] = saved_t;
        if (b > 0) rotations[b - 1] = saved_q;
      }
      const double numeric = (r[0] - r[1]) / (2.0 * h);
      // Central differences at h = 1e-6: truncation ~1e-12 x the third derivative, rounding
      // ~1e-16 |r| / h ~ 1e-10.
      EXPECT_NEAR(analytic[k], numeric, 1e-7 * std::max(1.0, std::abs(numeric)))
          << label << " block " << b << " axis " << k;
    }
  }
}

TEST_F(FloorResidualTest, JacobianMatchesCentralDifferencesOnTheManifoldUnderAndAbove) {
  for (const testing::NamedPose& sample : testing::ResidualPoseSweep(skeleton_, 31)) {
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, sample.pose, &fk);
    for (int k : Joints()) {
      // 0.3 units under and above: the 1e-6 steps stay on one side of the kink.
      for (double offset : {0.3, -0.3}) {
        const double lowest = fk.world_positions[k].y() + offset;
        FloorResidual residual(&skeleton_, k, &lowest, &scale_);
        ExpectTangentJacobianMatchesCentralDifferences(residual, sample.pose,
                                                       sample.name + " joint " + std::to_string(k));
      }
    }
  }
}

TEST_F(FloorResidualTest, MatchesAutodiffTwin) {
  for (const testing::NamedPose& sample : testing::ResidualPoseSweep(skeleton_, 31)) {
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, sample.pose, &fk);
    for (int k : Joints()) {
      for (double offset : {0.3, -0.3}) {
        const double lowest = fk.world_positions[k].y() + offset;
        FloorResidual residual(&skeleton_, k, &lowest, &scale_);
        ceres::DynamicAutoDiffCostFunction<FloorTwin, 4> twin(
            new FloorTwin{&skeleton_, lowest, scale_, residual.joints()});
        twin.AddParameterBlock(3);
        std::vector<const double*> parameters = {sample.pose.translations[0].data()};
        for (int j : residual.joints()) {
          twin.AddParameterBlock(4);
          parameters.push_back(sample.pose.rotations[j].coeffs().data());
        }
        twin.SetNumResiduals(1);
        const size_t nb = parameters.size();
        std::vector<std::vector<double>> ja(nb), jt(nb);
        std::vector<double*> pa(nb), pt(nb);
        for (size_t b = 0; b < nb; ++b) {
          ja[b].assign(b == 0 ? 3 : 4, 7.0);  // Non-zero: the residual must write every entry.
          jt[b].assign(b == 0 ? 3 : 4, 0.0);
          pa[b] = ja[b].data();
          pt[b] = jt[b].data();
        }
        double ra = 0.0, rt = 0.0;
        ASSERT_TRUE(residual.Evaluate(parameters.data(), &ra, pa.data()));
        ASSERT_TRUE(twin.Evaluate(parameters.data(), &rt, pt.data()));
        // Residuals are O(1): 1e-9 absolute is float-free agreement.
        EXPECT_NEAR(ra, rt, 1e-9) << sample.name;
        EXPECT_NEAR(ra, offset > 0.0 ? -scale_ * offset : 0.0, 1e-9) << sample.name;
        for (size_t b = 0; b < nb; ++b) {
          for (size_t i = 0; i < ja[b].size(); ++i) {
            // Relative 1e-10: the twin differentiates the same FK in dual numbers.
            EXPECT_NEAR(ja[b][i], jt[b][i], 1e-10 * std::max(1.0, std::abs(jt[b][i])))
                << sample.name << " joint " << k << " block " << b << " entry " << i << " offset " << offset;
          }
        }
        double rn = 0.0;
        ASSERT_TRUE(residual.Evaluate(parameters.data(), &rn, nullptr));
        EXPECT_EQ(rn, ra);
      }
    }
  }
}

// The floor in the frame solve: goals from a pose whose last joint is low; a floor above it.
class FloorSolveTest : public ::testing::Test {
 protected:
  FloorSolveTest() : rng_(23), skeleton_(testing::MakeTestSkeleton()), mesh_(testing::MakeTestMesh(skeleton_, &rng_)) {
    for (int v = 0; v < mesh_.num_vertices(); ++v) {
      TrackedVertex t;
      t.source_vertex = t.target_vertex = v;
      t.track_position = v % 3 != 1;
      setup_.tracked.push_back(t);
    }
    Pose truth = RestPose(skeleton_);
    std::mt19937 rng(5);
    Pose random = testing::RandomPose(skeleton_, &rng, 0.5);
    for (int j = 0; j < skeleton_.num_joints(); ++j) truth.rotations[j] = random.rotations[j];
    truth.translations[0] = random.translations[0];
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, truth, &fk);
    std::vector<Eigen::Isometry3d> transforms;
    ComputeSkinningTransforms(mesh_, fk, &transforms);
    SkinMesh(mesh_, transforms, &goal_positions_, &goal_normals_);
    foot_ = skeleton_.num_joints() - 1;
    truth_height_ = fk.world_positions[foot_].y();
  }
  RetargetSolveOptions Options(SolverKind kind, double floor_weight, double lowest) const {
    RetargetSolveOptions options;
    options.solver = kind;
    options.iterations = 20;
    options.floor_joints = {foot_};
    options.floor_heights = {lowest};
    options.floor_weight = floor_weight;
    options.ceres = DefaultRetargetCeresOptions();
    return options;
  }
  double SolvedHeight(const RetargetSolveOptions& options) {
    RetargetFrameSolver solver(skeleton_, mesh_, setup_, sigma_, options);
    Pose pose = RestPose(skeleton_);
    RetargetFrameReport report;
    EXPECT_TRUE(solver.Solve(goal_positions_, goal_normals_, &pose, &report).ok());
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, pose, &fk);
    return fk.world_positions[foot_].y();
  }
  std::mt19937 rng_;
  Skeleton skeleton_;
  SkinnedMesh mesh_;
  RetargetSetup setup_;
  Eigen::Matrix3Xd goal_positions_, goal_normals_;
  int foot_ = 0;
  double truth_height_ = 0.0;
  const double sigma_ = 0.4;
};

TEST_F(FloorSolveTest, EverySolverLiftsTheJointOutOfTheFloor) {
  const double lowest = truth_height_ + 0.2;  // The goals put the joint 0.2 under its floor.
  for (SolverKind kind : {SolverKind::kDls, SolverKind::kDlsGeneric, SolverKind::kCeres}) {
    const double free = SolvedHeight(Options(kind, 0.0, lowest));
    const double floored = SolvedHeight(Options(kind, 30.0, lowest));
    EXPECT_LT(free, lowest - 0.1) << SolverKindName(kind);
    // Soft, at weight 30 per sigma against ~27 position vertices of weight 1 that agree on
    // another pose: the lean kernel's rounds end within 2 % of sigma, Ceres' LM within 10 % of
    // the depth; the generic DLS (fixed lambda 5, 20 steps, the hinge's rows only where
    // still under) lifts it by a third of the depth.
    const double depth = lowest - free;
    const double bound = kind == SolverKind::kDls     ? lowest - 0.02 * sigma_
                         : kind == SolverKind::kCeres ? lowest - 0.1 * depth
                                                      : free + depth / 3.0;
    EXPECT_GT(floored, bound) << SolverKindName(kind) << " free " << free << " floored " << floored;
  }
}

TEST_F(FloorSolveTest, AFloorBelowChangesNothing) {
  const double lowest = truth_height_ - 0.5;
  for (SolverKind kind : {SolverKind::kDls, SolverKind::kDlsGeneric, SolverKind::kCeres}) {
    EXPECT_NEAR(SolvedHeight(Options(kind, 30.0, lowest)), SolvedHeight(Options(kind, 0.0, lowest)), 1e-12)
        << SolverKindName(kind);
  }
}

TEST(FloorOptionsTest, RejectsMismatchedHeightsAndNegativeWeights) {
  RetargetSolveOptions options;
  std::string error;
  options.floor_joints = {1, 2};
  options.floor_heights = {0.0};
  EXPECT_FALSE(options.IsValid(&error));
  options.floor_heights = {0.0, 0.1};
  options.floor_weight = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
  options.floor_weight = 10.0;
  EXPECT_TRUE(options.IsValid(&error)) << error;
}

}  // namespace
}  // namespace mocapsolve
