// LeftOfCharacter and the facing it signs (ComputeCharacterFrame): a figure whose lowest
// vertices lie behind it (heels, a bind pose with the feet turned back) faces backwards by
// the mesh alone; the roles' left turns it the right way, and a mesh without roles keeps
// the old rule.
#include "problems/retarget/role_sides.h"

#include <gtest/gtest.h>

#include "problems/retarget/mesh_mapping.h"

namespace mocapsolve {
namespace {

// A wide, flat "figure" facing +z: shoulders along x at height 1.5, lowest points behind
// (z = -0.1) at the floor.
Eigen::Matrix3Xd HeelsBehind() {
  Eigen::Matrix3Xd p(3, 6);
  p << -0.5, 0.5, -0.2, 0.2, -0.1, 0.1,  //
      1.5, 1.5, 0.8, 0.8, 0.0, 0.0,      //
      0.0, 0.0, 0.0, 0.0, -0.1, -0.1;
  return p;
}

TEST(RoleSidesTest, TheRolesLeftSignsTheFacing) {
  const Eigen::Matrix3Xd p = HeelsBehind();
  // Forward (+z) maps onto +Z when the facing is right.
  const Eigen::Vector3d by_mesh = ComputeCharacterFrame(p).facing * Eigen::Vector3d::UnitZ();
  EXPECT_LT(by_mesh.z(), -0.99);  // The mesh alone: turned around.
  const Eigen::Vector3d left(1.0, 0.0, 0.0);  // Facing +z with +y up, the left is +x.
  const Eigen::Vector3d by_roles = ComputeCharacterFrame(p, true, left).facing * Eigen::Vector3d::UnitZ();
  EXPECT_GT(by_roles.z(), 0.99);
  // A left with no horizontal part leaves the mesh's rule.
  EXPECT_LT((ComputeCharacterFrame(p, true, Eigen::Vector3d::UnitY()).facing * Eigen::Vector3d::UnitZ()).z(), -0.99);
}

TEST(RoleSidesTest, LeftFromTheVerticesOnEachSidesParts) {
  // pelvis (0) with a left (1) and a right (2) thigh; a left foot (3) without a role.
  std::vector<JointSpec> joints(4);
  const char* names[4] = {"pelvis", "l_thigh", "r_thigh", "l_foot"};
  const int parents[4] = {-1, 0, 0, 1};
  const Eigen::Vector3d offsets[4] = {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0.2, 0, 0), Eigen::Vector3d(-0.2, 0, 0),
                                      Eigen::Vector3d(0, -0.9, 0)};
  for (int j = 0; j < 4; ++j) {
    joints[j].name = names[j];
    joints[j].parent = parents[j];
    joints[j].offset = offsets[j];
  }
  Skeleton skeleton;
  ASSERT_TRUE(Skeleton::Create(joints, {}, Metres(), &skeleton).ok());
  SkinnedMeshSpec spec;
  spec.rest_positions.resize(3, 3);
  spec.rest_positions << 0.2, -0.2, 0.2,  //
      0.5, 0.5, 0.05,                     //
      0.0, 0.0, 0.0;
  spec.influences = {{{1, 1.0}}, {{2, 0.7}, {0, 0.3}}, {{3, 1.0}}};
  spec.joint_from_bind.assign(4, Eigen::Isometry3d::Identity());
  SkinnedMesh mesh;
  ASSERT_TRUE(SkinnedMesh::Create(skeleton, spec, &mesh).ok());
  HumanoidRoles roles;
  roles.humanoid = true;
  roles.roles = {{"pelvis", 0}, {"left_thigh", 1}, {"right_thigh", 2}};
  const Eigen::Vector3d left = LeftOfCharacter(skeleton, mesh, roles, Eigen::Matrix3d::Identity());
  EXPECT_NEAR(left.x(), 0.4, 1e-12);  // Left mean (0.2, 0.275, 0) minus right (-0.2, 0.5, 0).
  EXPECT_NEAR(left.y(), -0.225, 1e-12);
  // Turned into a world where the character's bind space is rotated 90 degrees about y.
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_LT((LeftOfCharacter(skeleton, mesh, roles, turn) - turn * left).norm(), 1e-12);
  roles.humanoid = false;
  EXPECT_EQ(LeftOfCharacter(skeleton, mesh, roles, Eigen::Matrix3d::Identity()), Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace mocapsolve
