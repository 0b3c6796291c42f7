#include "tests/character_variants.h"

#include <random>

#include <gtest/gtest.h>

#include "kinematics/skinning.h"

namespace mocapsolve::testing {

Variant AsRead(const GltfCharacter& character) {
  Variant v;
  v.name = "file as read";
  v.skeleton = character.skeleton;
  v.mesh = character.mesh;
  v.pose = character.rest_pose;
  v.bind_pose = character.bind_pose;
  return v;
}

Eigen::Isometry3d WorldFromJoint(const FkData& fk, int j) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = fk.world_rotations[j].toRotationMatrix();
  t.translation() = fk.world_positions[j];
  return t;
}

Variant Repose(const GltfCharacter& character, const std::vector<int>& arms, double arm_deg, double yaw_deg,
               bool rename, const std::string& name) {
  const Skeleton& skeleton = character.skeleton;
  Pose pose = character.rest_pose;
  FkData fk(skeleton);
  for (int a : arms) {
    ForwardKinematics(skeleton, pose, &fk);
    const int child = [&] {
      for (int j = 0; j < skeleton.num_joints(); ++j) {
        if (skeleton.parent(j) == a) return j;
      }
      return -1;
    }();
    const Eigen::Vector3d along = (fk.world_positions[child] - fk.world_positions[a]).normalized();
    const Eigen::Vector3d axis = along.cross(-Eigen::Vector3d::UnitY()).normalized();
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(arm_deg * M_PI / 180.0, axis));
    const Eigen::Quaterniond& world = fk.world_rotations[a];
    pose.rotations[a] = pose.rotations[a] * (world.conjugate() * turn * world);  // W' = turn W.
  }
  ForwardKinematics(skeleton, pose, &fk);
  const Eigen::Quaterniond yaw(Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()));
  const Eigen::Quaterniond root_world = fk.world_rotations[0];
  const Eigen::Vector3d root_position = fk.world_positions[0];
  pose.rotations[0] = pose.rotations[0] * (root_world.conjugate() * yaw * root_world);
  ForwardKinematics(skeleton, pose, &fk);
  pose.translations[0] += yaw * root_position - fk.world_positions[0];
  ForwardKinematics(skeleton, pose, &fk);

  Variant v;
  v.name = name;
  std::vector<JointSpec> specs;
  std::mt19937 rng(7);
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    specs.push_back(skeleton.joint(j));
    if (rename) specs.back().name = "n" + std::to_string(rng() % 1000000) + "_" + std::to_string(j);
  }
  EXPECT_TRUE(Skeleton::Create(specs, {}, skeleton.unit(), &v.skeleton).ok());
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(character.mesh, fk, &transforms);
  SkinnedMeshSpec spec;
  SkinMesh(character.mesh, transforms, &spec.rest_positions,
           character.mesh.has_normals() ? &spec.rest_normals : nullptr);
  spec.influences.resize(character.mesh.num_vertices());
  for (int i = 0; i < character.mesh.num_vertices(); ++i) {
    for (int k = character.mesh.weight_begin(i); k < character.mesh.weight_end(i); ++k) {
      spec.influences[i].push_back({character.mesh.weight_joint(k), character.mesh.weight(k)});
    }
  }
  for (int j = 0; j < skeleton.num_joints(); ++j) spec.joint_from_bind.push_back(WorldFromJoint(fk, j).inverse());
  EXPECT_TRUE(SkinnedMesh::Create(v.skeleton, spec, &v.mesh).ok());
  v.pose = pose;
  return v;
}

}  // namespace mocapsolve::testing
