// Small hand-made rigs for the kinematics tests: a branching skeleton with rest
// rotations, a zero-length bone and an animated non-root translation, and a skinned
// mesh on it with vertices weighted across several (also non-ancestor) bones.
#ifndef MOCAPSOLVE_TESTS_KINEMATICS_TEST_RIGS_H_
#define MOCAPSOLVE_TESTS_KINEMATICS_TEST_RIGS_H_

#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"

namespace mocapsolve::testing {

//            0 root
//            |
//            1 spine ---- 2 chest -- 3 neck(zero length) -- 4 head
//                            \-- 5 l_arm -- 6 l_hand
//                             \- 7 r_arm -- 8 r_hand
//            0 \-- 9 leg(animated translation) -- 10 foot
inline Skeleton MakeTestSkeleton() {
  auto joint = [](const char* name, int parent, Eigen::Vector3d offset, Eigen::Quaterniond rest) {
    JointSpec spec;
    spec.name = name;
    spec.parent = parent;
    spec.offset = offset;
    spec.rest_rotation = rest;
    return spec;
  };
  const Eigen::Quaterniond id = Eigen::Quaterniond::Identity();
  const Eigen::Quaterniond tilt = ExpMap(Eigen::Vector3d(0.3, -0.2, 0.5));
  std::vector<JointSpec> joints = {
      joint("root", -1, {0.0, 1.0, 0.0}, ExpMap(Eigen::Vector3d(0.0, 0.4, 0.0))),
      joint("spine", 0, {0.0, 0.2, 0.05}, id),
      joint("chest", 1, {0.01, 0.25, 0.0}, tilt),
      joint("neck", 2, {0.0, 0.0, 0.0}, id),  // Zero-length bone.
      joint("head", 3, {0.0, 0.12, 0.02}, id),
      joint("l_arm", 2, {0.15, 0.1, 0.0}, tilt.conjugate()),
      joint("l_hand", 5, {0.3, 0.0, 0.01}, id),
      joint("r_arm", 2, {-0.15, 0.1, 0.0}, id),
      joint("r_hand", 7, {-0.3, 0.02, 0.0}, id),
      joint("leg", 0, {0.1, -0.1, 0.0}, id),
      joint("foot", 9, {0.0, -0.8, 0.1}, id),
  };
  joints[0].channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition,
                        Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
  joints[9].channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition,
                        Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
  std::vector<EndSite> end_sites = {{"head_End", 4, {0.0, 0.1, 0.0}},
                                    {"foot_End", 10, {0.0, 0.0, 0.15}}};
  Skeleton skeleton;
  const Status status = Skeleton::Create(joints, end_sites, Metres(), &skeleton);
  EXPECT_TRUE(status.ok()) << status.message();
  return skeleton;
}

inline Pose RandomPose(const Skeleton& skeleton, std::mt19937* rng, double angle_scale = 1.0) {
  std::normal_distribution<double> normal;
  Pose pose = RestPose(skeleton);
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    pose.rotations[j] =
        ExpMap(angle_scale * Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng)));
  }
  pose.translations[0] += Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng));
  pose.translations[9] += 0.05 * Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng));
  return pose;
}

// The poses every residual's Jacobian test sweeps: zero rotation, three random, every
// joint near pi, every joint at gimbal lock (ZXY, 90 degrees). Non-root translations stay
// at the skeleton's offsets, as the residuals model them (RandomPose moves joint 9).
struct NamedPose {
  Pose pose;
  std::string name;
};
inline std::vector<NamedPose> ResidualPoseSweep(const Skeleton& skeleton, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<NamedPose> samples;
  samples.push_back({RestPose(skeleton), "zero rotation"});
  for (int i = 0; i < 3; ++i) samples.push_back({RandomPose(skeleton, &rng), "random"});
  Pose near_pi = RandomPose(skeleton, &rng);
  for (auto& q : near_pi.rotations) q = ExpMap(Eigen::Vector3d(0.0, kPi - 1e-7, 0.0));
  samples.push_back({near_pi, "near pi"});
  Pose gimbal = RandomPose(skeleton, &rng);
  for (auto& q : gimbal.rotations) q = QuaternionFromEuler(Eigen::Vector3d(0.4, kPi / 2, 0.2), EulerOrder::kZXY);
  samples.push_back({gimbal, "gimbal"});
  const Pose rest = RestPose(skeleton);
  for (NamedPose& sample : samples) {
    for (int j = 1; j < skeleton.num_joints(); ++j) sample.pose.translations[j] = rest.translations[j];
  }
  return samples;
}

// A mesh bound at the rest pose: a few vertices per bone, some weighted on 2-4 bones
// including bones in different branches (so thesis eq. 12 would be inexact).
inline SkinnedMesh MakeTestMesh(const Skeleton& skeleton, std::mt19937* rng) {
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> pick(0, skeleton.num_joints() - 1);
  std::uniform_real_distribution<double> uniform(0.05, 1.0);
  FkData bind(skeleton);
  ForwardKinematics(skeleton, RestPose(skeleton), &bind);
  SkinnedMeshSpec spec;
  const int nv = 40;
  spec.rest_positions.resize(3, nv);
  spec.rest_normals.resize(3, nv);
  for (int i = 0; i < nv; ++i) {
    const int main_joint = i % skeleton.num_joints();
    spec.rest_positions.col(i) = bind.world_positions[main_joint] +
                                 0.1 * Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng));
    spec.rest_normals.col(i) =
        Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng)).normalized();
    std::vector<SkinInfluence> influences = {{main_joint, uniform(*rng)}};
    for (int extra = 0; extra < i % 4; ++extra) influences.push_back({pick(*rng), uniform(*rng)});
    spec.influences.push_back(influences);
  }
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    Eigen::Isometry3d world_from_joint = Eigen::Isometry3d::Identity();
    world_from_joint.linear() = bind.world_rotations[j].toRotationMatrix();
    world_from_joint.translation() = bind.world_positions[j];
    spec.joint_from_bind.push_back(world_from_joint.inverse());
  }
  SkinnedMesh mesh;
  const Status status = SkinnedMesh::Create(skeleton, spec, &mesh);
  EXPECT_TRUE(status.ok()) << status.message();
  return mesh;
}

}  // namespace mocapsolve::testing

#endif  // MOCAPSOLVE_TESTS_KINEMATICS_TEST_RIGS_H_
