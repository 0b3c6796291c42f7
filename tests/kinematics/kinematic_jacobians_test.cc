// The analytic pose Jacobians of joint positions, blended points, skinned positions
// and skinned normals against (1) central differences taken on the manifold
// (R_j <- R_j exp(+-h e_k)) and (2) an autodiff twin: the same FK/LBS templated on
// ceres::Jet, differentiated at delta = 0.
#include "kinematics/kinematic_jacobians.h"

#include <functional>
#include <random>

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include "kinematics/marker_set.h"
#include "kinematics/skinning.h"
#include "tests/kinematics/test_rigs.h"

namespace mocapsolve {
namespace {

// A point rigidly attached to joint b at `local` (joint frame), blended with `weight`.
struct LocalTerm {
  int joint;
  double weight;
  Eigen::Vector3d local;
};

template <typename T>
Eigen::Quaternion<T> ExpMapTwin(const T* v) {
  const T theta_sq = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  T w, scale;
  if (theta_sq < T(1e-12)) {
    w = T(1.0) - theta_sq / T(8.0);
    scale = T(0.5) - theta_sq / T(48.0);
  } else {
    const T theta = sqrt(theta_sq);
    w = cos(theta / T(2.0));
    scale = sin(theta / T(2.0)) / theta;
  }
  return Eigen::Quaternion<T>(w, scale * v[0], scale * v[1], scale * v[2]);
}

// sum_b w_b (world_from_joint_b(pose + delta) * local_b); rotation only if `direction`.
template <typename T>
Eigen::Matrix<T, 3, 1> BlendedPointTwin(const Skeleton& s, const Pose& pose,
                                        const std::vector<LocalTerm>& terms, bool direction,
                                        const T* delta) {
  const int nj = s.num_joints();
  std::vector<Eigen::Quaternion<T>> rotation(nj);
  std::vector<Eigen::Matrix<T, 3, 1>> position(nj);
  for (int j = 0; j < nj; ++j) {
    const Eigen::Quaternion<T> local = s.rest_rotation(j).cast<T>() *
                                       pose.rotations[j].cast<T>() *
                                       ExpMapTwin(delta + RotationColumn(j));
    Eigen::Matrix<T, 3, 1> t = pose.translations[j].cast<T>();
    if (j == 0) {
      t += Eigen::Matrix<T, 3, 1>(delta[0], delta[1], delta[2]);
      position[0] = t;
      rotation[0] = local;
    } else {
      const int p = s.parent(j);
      position[j] = position[p] + rotation[p] * t;
      rotation[j] = rotation[p] * local;
    }
  }
  Eigen::Matrix<T, 3, 1> sum = Eigen::Matrix<T, 3, 1>::Zero();
  for (const LocalTerm& term : terms) {
    Eigen::Matrix<T, 3, 1> p = rotation[term.joint] * term.local.cast<T>();
    if (!direction) p += position[term.joint];
    sum += T(term.weight) * p;
  }
  return sum;
}

constexpr int kMaxTangent = 3 + 3 * 11;
using JetT = ceres::Jet<double, kMaxTangent>;

PoseJacobian TwinJacobian(const Skeleton& s, const Pose& pose, const std::vector<LocalTerm>& terms,
                          bool direction) {
  const int n = PoseTangentSize(s);
  EXPECT_EQ(n, kMaxTangent);
  std::vector<JetT> delta(n);
  for (int i = 0; i < n; ++i) delta[i] = JetT(0.0, i);
  const Eigen::Matrix<JetT, 3, 1> x = BlendedPointTwin(s, pose, terms, direction, delta.data());
  PoseJacobian jacobian(3, n);
  for (int r = 0; r < 3; ++r) jacobian.row(r) = x[r].v.transpose();
  return jacobian;
}

PoseJacobian CentralDifferences(const Skeleton& s, const Pose& pose,
                                const std::function<Eigen::Vector3d(const Pose&)>& f) {
  const int n = PoseTangentSize(s);
  const double h = 1e-6;
  PoseJacobian jacobian(3, n);
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
    step[i] = h;
    Pose plus = pose, minus = pose;
    RetractPose(step, &plus);
    RetractPose(-step, &minus);
    jacobian.col(i) = (f(plus) - f(minus)) / (2.0 * h);
  }
  return jacobian;
}

// Poses to sweep: random, zero rotation, near gimbal lock of a ZXY decomposition, and
// every joint rotated by almost pi (where exp/log branches change).
std::vector<Pose> SweepPoses(const Skeleton& s) {
  std::mt19937 rng(42);
  std::vector<Pose> poses;
  for (int i = 0; i < 4; ++i) poses.push_back(testing::RandomPose(s, &rng));
  poses.push_back(RestPose(s));
  Pose gimbal = testing::RandomPose(s, &rng);
  for (auto& q : gimbal.rotations) {
    q = QuaternionFromEuler(Eigen::Vector3d(0.7, kPi / 2 - 1e-9, -0.4), EulerOrder::kZXY);
  }
  poses.push_back(gimbal);
  Pose near_pi = testing::RandomPose(s, &rng);
  std::normal_distribution<double> normal;
  for (auto& q : near_pi.rotations) {
    q = ExpMap((kPi - 1e-7) * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
  }
  poses.push_back(near_pi);
  return poses;
}

// Central differences with h = 1e-6 on coordinates of order 1 m: truncation ~h^2 and
// round-off ~1e-16/h, so agreement to 1e-7 is what they can show.
constexpr double kNumericTolerance = 1e-7;
// The twin computes the same derivative in a different order of operations.
constexpr double kTwinTolerance = 1e-11;

class KinematicJacobians : public ::testing::Test {
 protected:
  Skeleton skeleton_ = testing::MakeTestSkeleton();
};

TEST_F(KinematicJacobians, JointPositions) {
  for (const Pose& pose : SweepPoses(skeleton_)) {
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, pose, &fk);
    for (int joint = 0; joint < skeleton_.num_joints(); ++joint) {
      PoseJacobian analytic;
      JointPositionJacobian(skeleton_, fk, joint, &analytic);
      const PoseJacobian numeric = CentralDifferences(skeleton_, pose, [&](const Pose& p) {
        FkData d(skeleton_);
        ForwardKinematics(skeleton_, p, &d);
        return d.world_positions[joint];
      });
      EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), kNumericTolerance) << "joint " << joint;
      const PoseJacobian twin = TwinJacobian(skeleton_, pose, {{joint, 1.0, Eigen::Vector3d::Zero()}}, false);
      EXPECT_LT((analytic - twin).cwiseAbs().maxCoeff(), kTwinTolerance) << "joint " << joint;
    }
  }
}

TEST_F(KinematicJacobians, BlendedPointsAcrossBranches) {
  // A marker blended over bones of different branches (l_hand, r_arm, foot): thesis
  // eq. 12's w^_j (x - o_j) form would be wrong here; ours must not be.
  const std::vector<LocalTerm> terms = {{6, 0.5, {0.02, 0.03, -0.01}},
                                        {7, 0.3, {0.1, 0.0, 0.05}},
                                        {10, 0.2, {0.0, 0.01, 0.1}}};
  for (const Pose& pose : SweepPoses(skeleton_)) {
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, pose, &fk);
    std::vector<BlendTerm> blend;
    for (const LocalTerm& t : terms) {
      blend.push_back({t.joint, t.weight, fk.world_positions[t.joint] + fk.world_rotations[t.joint] * t.local});
    }
    PoseJacobian analytic = PoseJacobian::Zero(3, PoseTangentSize(skeleton_));
    AccumulateBlendedPointJacobian(skeleton_, fk, blend, &analytic);
    const PoseJacobian twin = TwinJacobian(skeleton_, pose, terms, false);
    EXPECT_LT((analytic - twin).cwiseAbs().maxCoeff(), kTwinTolerance);
    const PoseJacobian numeric = CentralDifferences(skeleton_, pose, [&](const Pose& p) {
      FkData d(skeleton_);
      ForwardKinematics(skeleton_, p, &d);
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (const LocalTerm& t : terms) x += t.weight * (d.world_positions[t.joint] + d.world_rotations[t.joint] * t.local);
      return x;
    });
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), kNumericTolerance);
  }
}

TEST_F(KinematicJacobians, MarkerSetJacobianStacksTheBlendedPointJacobians) {
  // MarkerSetJacobian (kinematics/marker_set.h) writes the same formula into one big
  // matrix; it must equal the per-marker AccumulateBlendedPointJacobian (checked above
  // against the twin and differences) to round-off, blended markers included.
  std::vector<MarkerSpec> specs = {{"single", {{4, 1.0, {0.02, 0.1, -0.03}}}},
                                   {"blended", {{6, 0.5, {0.02, 0.03, -0.01}}, {7, 0.3, {0.1, 0.0, 0.05}},
                                                {10, 0.2, {0.0, 0.01, 0.1}}}},
                                   {"root", {{0, 1.0, {0.1, 0.0, 0.0}}}}};
  MarkerSet markers;
  ASSERT_TRUE(MarkerSet::Create(skeleton_, specs, &markers).ok());
  std::vector<Eigen::Matrix3d> scratch;
  Eigen::MatrixXd stacked;
  for (const Pose& pose : SweepPoses(skeleton_)) {
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, pose, &fk);
    MarkerSetJacobian(skeleton_, markers, fk, &scratch, &stacked);
    ASSERT_EQ(stacked.rows(), 3 * markers.num_markers());
    ASSERT_EQ(stacked.cols(), PoseTangentSize(skeleton_));
    std::vector<BlendTerm> blend;
    for (int m = 0; m < markers.num_markers(); ++m) {
      markers.BlendTerms(m, fk, &blend);
      PoseJacobian one = PoseJacobian::Zero(3, PoseTangentSize(skeleton_));
      AccumulateBlendedPointJacobian(skeleton_, fk, blend, &one);
      // Same products in another order: round-off only.
      EXPECT_LT((stacked.middleRows(3 * m, 3) - one).cwiseAbs().maxCoeff(), 1e-12) << markers.label(m);
    }
  }
}

TEST_F(KinematicJacobians, SkinnedPositionsAndNormals) {
  std::mt19937 rng(5);
  const SkinnedMesh mesh = testing::MakeTestMesh(skeleton_, &rng);
  for (const Pose& pose : SweepPoses(skeleton_)) {
    FkData fk(skeleton_);
    ForwardKinematics(skeleton_, pose, &fk);
    std::vector<Eigen::Isometry3d> transforms;
    ComputeSkinningTransforms(mesh, fk, &transforms);
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      std::vector<LocalTerm> position_terms, normal_terms;
      for (int k = mesh.weight_begin(v); k < mesh.weight_end(v); ++k) {
        const int b = mesh.weight_joint(k);
        position_terms.push_back({b, mesh.weight(k), mesh.joint_from_bind(b) * Eigen::Vector3d(mesh.rest_positions().col(v))});
        normal_terms.push_back({b, mesh.weight(k), mesh.joint_from_bind(b).linear() * mesh.rest_normals().col(v)});
      }
      PoseJacobian position_jacobian, normal_jacobian;
      SkinnedPositionJacobian(skeleton_, mesh, fk, transforms, v, &position_jacobian);
      SkinnedNormalJacobian(skeleton_, mesh, fk, transforms, v, &normal_jacobian);
      EXPECT_LT((position_jacobian - TwinJacobian(skeleton_, pose, position_terms, false)).cwiseAbs().maxCoeff(), kTwinTolerance) << v;
      EXPECT_LT((normal_jacobian - TwinJacobian(skeleton_, pose, normal_terms, true)).cwiseAbs().maxCoeff(), kTwinTolerance) << v;

      auto skinned = [&](const Pose& p, bool normal) {
        FkData d(skeleton_);
        ForwardKinematics(skeleton_, p, &d);
        std::vector<Eigen::Isometry3d> t;
        ComputeSkinningTransforms(mesh, d, &t);
        return normal ? SkinNormal(mesh, t, v) : SkinPosition(mesh, t, v);
      };
      const PoseJacobian numeric_position = CentralDifferences(skeleton_, pose, [&](const Pose& p) { return skinned(p, false); });
      const PoseJacobian numeric_normal = CentralDifferences(skeleton_, pose, [&](const Pose& p) { return skinned(p, true); });
      EXPECT_LT((position_jacobian - numeric_position).cwiseAbs().maxCoeff(), kNumericTolerance) << v;
      EXPECT_LT((normal_jacobian - numeric_normal).cwiseAbs().maxCoeff(), kNumericTolerance) << v;
    }
  }
}

TEST_F(KinematicJacobians, ThesisEquation12IsInexactForSplitWeights) {
  // Documents why DESIGN.md replaces eq. 12: for a vertex weighted 50/50 on l_hand and
  // r_hand, the column of l_arm by eq. 12, a_k x (w^_j (x - o_j)), differs from the
  // exact a_k x (sum_{b in subtree} w_b p_b - w^_j o_j).
  std::mt19937 rng(9);
  const Pose pose = testing::RandomPose(skeleton_, &rng);
  FkData fk(skeleton_);
  ForwardKinematics(skeleton_, pose, &fk);
  const Eigen::Vector3d p_left = fk.world_positions[6] + fk.world_rotations[6] * Eigen::Vector3d(0.05, 0, 0);
  const Eigen::Vector3d p_right = fk.world_positions[8] + fk.world_rotations[8] * Eigen::Vector3d(-0.05, 0, 0);
  PoseJacobian exact = PoseJacobian::Zero(3, PoseTangentSize(skeleton_));
  AccumulateBlendedPointJacobian(skeleton_, fk, {{6, 0.5, p_left}, {8, 0.5, p_right}}, &exact);
  const Eigen::Vector3d x = 0.5 * (p_left + p_right);
  const int arm = 5;
  const Eigen::Matrix3d axes = fk.world_rotations[arm].toRotationMatrix();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d eq12 = axes.col(k).cross(0.5 * (x - fk.world_positions[arm]));
    const Eigen::Vector3d exact_column = exact.col(RotationColumn(arm) + k);
    EXPECT_GT((eq12 - exact_column).norm(), 1e-3);
  }
}

}  // namespace
}  // namespace mocapsolve
