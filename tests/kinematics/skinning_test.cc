#include "kinematics/skinning.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "tests/kinematics/test_rigs.h"

namespace mocapsolve {
namespace {

TEST(Skinning, BindPoseReproducesRestMesh) {
  const Skeleton s = testing::MakeTestSkeleton();
  std::mt19937 rng(1);
  const SkinnedMesh mesh = testing::MakeTestMesh(s, &rng);
  FkData fk(s);
  ForwardKinematics(s, RestPose(s), &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(mesh, fk, &transforms);
  Eigen::Matrix3Xd positions, normals;
  SkinMesh(mesh, transforms, &positions, &normals);
  EXPECT_LT((positions - mesh.rest_positions()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((normals - mesh.rest_normals()).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Skinning, RigidlyBoundVertexFollowsItsJoint) {
  const Skeleton s = testing::MakeTestSkeleton();
  std::mt19937 rng(2);
  const SkinnedMesh mesh = testing::MakeTestMesh(s, &rng);
  const Pose pose = testing::RandomPose(s, &rng);
  FkData fk(s);
  ForwardKinematics(s, pose, &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(mesh, fk, &transforms);
  // Vertex 0 has a single influence (i % 4 == 0) on joint 0.
  ASSERT_EQ(mesh.weight_end(0) - mesh.weight_begin(0), 1);
  const int b = mesh.weight_joint(mesh.weight_begin(0));
  const Eigen::Vector3d local = mesh.joint_from_bind(b) * Eigen::Vector3d(mesh.rest_positions().col(0));
  EXPECT_LT((SkinPosition(mesh, transforms, 0) - (fk.world_positions[b] + fk.world_rotations[b] * local)).norm(), 1e-14);
}

TEST(Skinning, CumulativeWeightsSumOverSubtrees) {
  const Skeleton s = testing::MakeTestSkeleton();
  SkinnedMeshSpec spec;
  spec.rest_positions = Eigen::Matrix3Xd::Zero(3, 1);
  // Weights on head (4), l_hand (6) and foot (10); unnormalized, Create normalizes.
  spec.influences = {{{4, 2.0}, {6, 1.0}, {10, 1.0}}};
  spec.joint_from_bind.assign(s.num_joints(), Eigen::Isometry3d::Identity());
  SkinnedMesh mesh;
  ASSERT_TRUE(SkinnedMesh::Create(s, spec, &mesh).ok());
  EXPECT_DOUBLE_EQ(mesh.CumulativeWeight(s, 0, 0), 1.0);
  EXPECT_DOUBLE_EQ(mesh.CumulativeWeight(s, 0, 2), 0.75);   // chest: head + l_hand.
  EXPECT_DOUBLE_EQ(mesh.CumulativeWeight(s, 0, 3), 0.5);    // neck: head.
  EXPECT_DOUBLE_EQ(mesh.CumulativeWeight(s, 0, 9), 0.25);   // leg: foot.
  EXPECT_DOUBLE_EQ(mesh.CumulativeWeight(s, 0, 7), 0.0);    // r_arm.
}

TEST(Skinning, RejectsBadSkins) {
  const Skeleton s = testing::MakeTestSkeleton();
  SkinnedMeshSpec spec;
  spec.rest_positions = Eigen::Matrix3Xd::Zero(3, 2);
  spec.joint_from_bind.assign(s.num_joints(), Eigen::Isometry3d::Identity());
  SkinnedMesh mesh;
  spec.influences = {{{0, 1.0}}};
  EXPECT_FALSE(SkinnedMesh::Create(s, spec, &mesh).ok());  // Count mismatch.
  spec.influences = {{{0, 1.0}}, {}};
  EXPECT_FALSE(SkinnedMesh::Create(s, spec, &mesh).ok());  // Vertex without weight.
  spec.influences = {{{0, 1.0}}, {{99, 1.0}}};
  EXPECT_FALSE(SkinnedMesh::Create(s, spec, &mesh).ok());  // Bad joint.
  spec.influences = {{{0, 1.0}}, {{1, -0.5}}};
  EXPECT_FALSE(SkinnedMesh::Create(s, spec, &mesh).ok());  // Negative weight.
  spec.influences = {{{0, 1.0}}, {{1, std::nan("")}}};
  EXPECT_FALSE(SkinnedMesh::Create(s, spec, &mesh).ok());  // NaN weight.
  spec.influences = {{{0, 1.0}}, {{1, 1.0}}};
  spec.rest_positions(1, 1) = std::nan("");
  EXPECT_FALSE(SkinnedMesh::Create(s, spec, &mesh).ok());  // NaN vertex.
}

}  // namespace
}  // namespace mocapsolve
