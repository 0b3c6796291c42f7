// TrackedVertexResidual (positions and normals): GradientChecker on RightQuaternionManifold,
// an autodiff twin (the same residual templated on ceres::Jet), and equality with the
// kinematics layer's exact SkinnedPositionJacobian / SkinnedNormalJacobian. The test mesh
// weights vertices on 2-4 bones, also in different branches, so part of a vertex's
// weight lies outside the subtree of most chain joints (where thesis eq. 12 is inexact).
#include "problems/retarget/tracked_vertex_residual.h"

#include <algorithm>
#include <memory>
#include <random>
#include <string>

#include <ceres/dynamic_autodiff_cost_function.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/kinematic_jacobians.h"
#include "kinematics/rotation.h"
#include "kinematics/skinning.h"
#include "solvers/right_quaternion_manifold.h"
#include "tests/kinematics/test_rigs.h"

namespace mocapsolve {
namespace {

// The twin: FK along the chain on normalized quaternions, then LBS of the one vertex.
struct TrackedVertexTwin {
  const Skeleton* skeleton;
  const SkinnedMesh* mesh;
  int vertex;
  bool track_position;
  Eigen::Vector3d goal;
  double scale;
  std::vector<int> chain;

  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    std::vector<Eigen::Quaternion<T>> rotation(skeleton->num_joints());
    std::vector<Eigen::Matrix<T, 3, 1>> position(skeleton->num_joints());
    for (size_t s = 0; s < chain.size(); ++s) {
      const int j = chain[s];
      const T* p = parameters[1 + s];
      const T norm = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
      const Eigen::Quaternion<T> local =
          skeleton->rest_rotation(j).cast<T>() *
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
    for (int k = mesh->weight_begin(vertex); k < mesh->weight_end(vertex); ++k) {
      const int b = mesh->weight_joint(k);
      const Eigen::Isometry3d& jfb = mesh->joint_from_bind(b);
      if (track_position) {
        const Eigen::Vector3d z = jfb * mesh->rest_positions().col(vertex);
        x += T(mesh->weight(k)) * (position[b] + rotation[b] * z.cast<T>());
      } else {
        const Eigen::Vector3d y = jfb.linear() * mesh->rest_normals().col(vertex);
        x += T(mesh->weight(k)) * (rotation[b] * y.cast<T>());
      }
    }
    for (int i = 0; i < 3; ++i) residuals[i] = T(scale) * (x[i] - T(goal[i]));
    return true;
  }
};

class TrackedVertexResidualTest : public ::testing::Test {
 protected:
  TrackedVertexResidualTest() : rng_(5), skeleton_(testing::MakeTestSkeleton()),
                                mesh_(testing::MakeTestMesh(skeleton_, &rng_)) {}
  std::mt19937 rng_;
  Skeleton skeleton_;
  SkinnedMesh mesh_;
  Eigen::Vector3d goal_ = Eigen::Vector3d(0.3, 1.2, -0.4);
  const double scale_ = 2.5;
};

TEST_F(TrackedVertexResidualTest, GradientCheckerOnTheManifold) {
  RightQuaternionManifold quaternion_manifold;
  for (const testing::NamedPose& sample : testing::ResidualPoseSweep(skeleton_, 23)) {
    for (int v = 0; v < mesh_.num_vertices(); ++v) {
      for (bool position : {true, false}) {
        TrackedVertexResidual residual(&skeleton_, &mesh_, v, position, &goal_, scale_);
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
        // Probe's own verdict is purely relative and trips on entries that are zero up to
        // round-off; a mixed tolerance on its tangent Jacobians instead (central
        // differences are good to ~1e-8 on O(1) values).
        for (size_t b = 0; b < results.local_jacobians.size(); ++b) {
          const ceres::Matrix& analytic = results.local_jacobians[b];
          const ceres::Matrix& numeric = results.local_numeric_jacobians[b];
          const double error = (analytic - numeric).cwiseAbs().maxCoeff();
          EXPECT_LT(error, 1e-7 * std::max(1.0, numeric.cwiseAbs().maxCoeff()))
              << sample.name << " vertex " << v << (position ? " position" : " normal")
              << " block " << b << "\n" << results.error_log;
        }
      }
    }
  }
}

TEST_F(TrackedVertexResidualTest, MatchesAutodiffTwin) {
  for (const testing::NamedPose& sample : testing::ResidualPoseSweep(skeleton_, 23)) {
    for (int v = 0; v < mesh_.num_vertices(); ++v) {
      for (bool position : {true, false}) {
        TrackedVertexResidual residual(&skeleton_, &mesh_, v, position, &goal_, scale_);
        auto* functor = new TrackedVertexTwin{&skeleton_, &mesh_, v, position, goal_, scale_,
                                              residual.joints()};
        ceres::DynamicAutoDiffCostFunction<TrackedVertexTwin, 4> twin(functor);
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
          const int size = b == 0 ? 9 : 12;
          ja[b].assign(size, 0.0);
          jt[b].assign(size, 0.0);
          pa[b] = ja[b].data();
          pt[b] = jt[b].data();
        }
        double ra[3], rt[3];
        ASSERT_TRUE(residual.Evaluate(parameters.data(), ra, pa.data()));
        ASSERT_TRUE(twin.Evaluate(parameters.data(), rt, pt.data()));
        for (int i = 0; i < 3; ++i) {
          EXPECT_NEAR(ra[i], rt[i], 1e-9) << sample.name << " vertex " << v;  // Same FK, reordered sums.
        }
        for (size_t b = 0; b < nb; ++b) {
          for (size_t i = 0; i < ja[b].size(); ++i) {
            // Both are exact derivatives of the same function: round-off only.
            EXPECT_NEAR(ja[b][i], jt[b][i], 1e-10 * std::max(1.0, std::abs(jt[b][i])))
                << sample.name << " vertex " << v << (position ? " position" : " normal")
                << " block " << b << " entry " << i;
          }
        }
        // A null jacobians array and null blocks are allowed.
        double rn[3];
        ASSERT_TRUE(residual.Evaluate(parameters.data(), rn, nullptr));
        EXPECT_EQ(rn[0], ra[0]);
      }
    }
  }
}

// The residual's tangent blocks (ambient Jacobian times PlusJacobian) equal the kinematics
// layer's exact skinned-vertex Jacobians, column block by column block.
TEST_F(TrackedVertexResidualTest, AgreesWithKinematicJacobians) {
  for (const testing::NamedPose& sample : testing::ResidualPoseSweep(skeleton_, 23)) {
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, sample.pose, &fk);
    std::vector<Eigen::Isometry3d> transforms;
    ComputeSkinningTransforms(mesh_, fk, &transforms);
    for (int v = 0; v < mesh_.num_vertices(); ++v) {
      for (bool position : {true, false}) {
        PoseJacobian reference;
        if (position) {
          SkinnedPositionJacobian(skeleton_, mesh_, fk, transforms, v, &reference);
        } else {
          SkinnedNormalJacobian(skeleton_, mesh_, fk, transforms, v, &reference);
        }
        TrackedVertexResidual residual(&skeleton_, &mesh_, v, position, &goal_, scale_);
        std::vector<const double*> parameters = {sample.pose.translations[0].data()};
        for (int j : residual.joints()) parameters.push_back(sample.pose.rotations[j].coeffs().data());
        const size_t nb = parameters.size();
        std::vector<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> ambient(nb);
        Eigen::Matrix<double, 3, 3, Eigen::RowMajor> translation;
        std::vector<double*> jacobians(nb);
        jacobians[0] = translation.data();
        for (size_t b = 1; b < nb; ++b) jacobians[b] = ambient[b].data();
        double r[3];
        ASSERT_TRUE(residual.Evaluate(parameters.data(), r, jacobians.data()));
        const Eigen::Vector3d x = position ? SkinPosition(mesh_, transforms, v) : SkinNormal(mesh_, transforms, v);
        EXPECT_LT((Eigen::Map<Eigen::Vector3d>(r) - scale_ * (x - goal_)).norm(), 1e-12);
        EXPECT_LT((translation - scale_ * reference.leftCols<3>()).cwiseAbs().maxCoeff(), 1e-12);
        std::vector<bool> in_chain(skeleton_.num_joints(), false);
        for (size_t s = 0; s < residual.joints().size(); ++s) {
          const int j = residual.joints()[s];
          in_chain[j] = true;
          const Eigen::Matrix3d tangent =
              ambient[1 + s] * QuaternionPlusJacobian(sample.pose.rotations[j].coeffs().data());
          // Exact formulas on both sides; round-off on O(1) entries.
          EXPECT_LT((tangent - scale_ * reference.middleCols<3>(RotationColumn(j))).cwiseAbs().maxCoeff(), 1e-12)
              << sample.name << " vertex " << v << " joint " << j;
        }
        for (int j = 0; j < skeleton_.num_joints(); ++j) {
          if (!in_chain[j]) { EXPECT_EQ(reference.middleCols<3>(RotationColumn(j)).norm(), 0.0); }
        }
      }
    }
  }
}

}  // namespace
}  // namespace mocapsolve
