// Floor IK bones (floor_ik_bones.h) on RobotExpressive, whose Foot.L / Foot.R and pole
// targets are children of its root bone `Bone`: they are found, the feet anchored on the shins; the
// solve character keeps every joint's world transform in the bind and rest poses (so the
// surface is the same), and a pose of the solve character goes back onto the character with
// the same world transforms (the IK bones then carry translations). The five skinned
// shared humanoids have none. Skipped without MOCAPSOLVE_DATA.
#include <algorithm>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "io/gltf_reader.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/skinning.h"
#include "problems/retarget/floor_ik_bones.h"
#include "problems/retarget/joint_map.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

FloorIkBones Find(const GltfCharacter& c) {
  const JointMapSkeleton standing = StandingSkeleton(c.skeleton, c.bind_pose, &c.mesh, c.rest_pose);
  return FindFloorIkBones(c.skeleton, standing.positions, FindRoles(standing), &c.mesh);
}

// Largest difference of world positions and rotation angle (radians) between joint j of `a` at
// pose pa and the joint of the same name of `b` at pose pb, over all joints.
void WorldDifference(const Skeleton& a, const Pose& pa, const Skeleton& b, const Pose& pb, double* position,
                     double* angle) {
  FkData fa(a), fb(b);
  ForwardKinematics(a, pa, &fa);
  ForwardKinematics(b, pb, &fb);
  *position = *angle = 0.0;
  for (int j = 0; j < a.num_joints(); ++j) {
    const int k = b.FindJoint(a.name(j));
    ASSERT_GE(k, 0) << a.name(j);
    *position = std::max(*position, (fa.world_positions[j] - fb.world_positions[k]).norm());
    *angle = std::max(*angle, fa.world_rotations[j].angularDistance(fb.world_rotations[k]));
  }
}

TEST(FloorIkBonesTest, RobotExpressiveFeetAndPolesFollowTheirLegs) {
  MOCAPSOLVE_DATA_FILE(glb, "gltf/RobotExpressive.glb");
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(glb, GltfReadOptions(), &c).ok());
  const FloorIkBones ik = Find(c);
  std::printf("RobotExpressive floor IK bones: %s\n", ik.Describe(c.skeleton).c_str());
  ASSERT_EQ(ik.bones.size(), 4u) << ik.Describe(c.skeleton);
  for (size_t k = 0; k < ik.bones.size(); ++k) {
    const std::string bone = c.skeleton.name(ik.bones[k]);
    const std::string side = bone.substr(bone.size() - 2);  // ".L" / ".R".
    const std::string anchor = c.skeleton.name(ik.anchors[k]);
    // The feet on their shins; the pole targets, in front of the knees, on the body whose
    // surface (the torso's rigid mesh under `Body`) is nearest.
    if (bone.rfind("Foot", 0) == 0) {
      EXPECT_EQ(anchor, "LowerLeg" + side) << bone;
    } else {
      EXPECT_EQ(bone.rfind("PoleTarget", 0), 0u) << bone;
      EXPECT_EQ(anchor, "Body") << bone;
    }
  }

  FloorIkSolveCharacter solve;
  ASSERT_TRUE(MakeFloorIkSolveCharacter(c.skeleton, c.mesh, c.bind_pose, c.rest_pose, ik, &solve).ok());
  const int foot = solve.skeleton.FindJoint("Foot.L");
  EXPECT_TRUE(solve.skeleton.IsAncestorOrSelf(solve.skeleton.FindJoint("UpperLeg.L"), foot));
  double position = 0.0, angle = 0.0;
  // Tolerances: float-read glTF transforms composed a few times (1e-9 of ~1e2 units).
  WorldDifference(c.skeleton, c.bind_pose, solve.skeleton, solve.bind_pose, &position, &angle);
  EXPECT_LT(position, 1e-9);
  EXPECT_LT(angle, 1e-9);
  WorldDifference(c.skeleton, c.rest_pose, solve.skeleton, solve.rest_pose, &position, &angle);
  EXPECT_LT(position, 1e-9);
  EXPECT_LT(angle, 1e-9);
  // The skinned surface at the bind pose is the same (joint_from_bind follows the order).
  FkData fk_c(c.skeleton), fk_s(solve.skeleton);
  ForwardKinematics(c.skeleton, c.bind_pose, &fk_c);
  ForwardKinematics(solve.skeleton, solve.bind_pose, &fk_s);
  std::vector<Eigen::Isometry3d> tc, ts;
  ComputeSkinningTransforms(c.mesh, fk_c, &tc);
  ComputeSkinningTransforms(solve.mesh, fk_s, &ts);
  Eigen::Matrix3Xd vc, vs;
  SkinMesh(c.mesh, tc, &vc, nullptr);
  SkinMesh(solve.mesh, ts, &vs, nullptr);
  EXPECT_LT((vc - vs).cwiseAbs().maxCoeff(), 1e-9);

  // A random pose of the solve character, back onto the character: same world transforms; the
  // IK foot moved off its rest offset (a translation key); round trip back onto the solve.
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 0.4);
  Pose pose = solve.rest_pose;
  for (Eigen::Quaterniond& q : pose.rotations) {
    q = q * Eigen::Quaterniond(Eigen::AngleAxisd(normal(rng), Eigen::Vector3d(normal(rng), normal(rng), 1).normalized()));
  }
  const Pose on_character = FloorIkPoseOnCharacter(c.skeleton, ik, solve, pose);
  WorldDifference(solve.skeleton, pose, c.skeleton, on_character, &position, &angle);
  EXPECT_LT(position, 1e-9);
  EXPECT_LT(angle, 1e-9);
  const int foot_c = c.skeleton.FindJoint("Foot.L");
  EXPECT_GT((on_character.translations[foot_c] - c.rest_pose.translations[foot_c]).norm(), 1e-3);
  const Pose back = FloorIkPoseOnSolveCharacter(c.skeleton, ik, solve, on_character);
  WorldDifference(solve.skeleton, pose, solve.skeleton, back, &position, &angle);
  EXPECT_LT(position, 1e-9);
  EXPECT_LT(angle, 1e-9);
}

// The other shared humanoids (rooted at the pelvis, or with no branch off a floor root): none,
// so their retargets take the path they took before.
TEST(FloorIkBonesTest, SharedSkinnedHumanoidsHaveNone) {
  for (const char* name : {"Xbot", "Soldier", "CesiumMan", "Ely", "RiggedFigure"}) {
    MOCAPSOLVE_DATA_FILE(glb, std::string("gltf/") + name + ".glb");
    GltfCharacter c;
    ASSERT_TRUE(ReadGltfCharacter(glb, GltfReadOptions(), &c).ok()) << name;
    const FloorIkBones ik = Find(c);
    EXPECT_TRUE(ik.empty()) << name << ": " << ik.Describe(c.skeleton);
  }
}

}  // namespace
}  // namespace mocapsolve
