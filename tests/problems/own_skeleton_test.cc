// A motion on the target's own skeleton comes back as itself (problems/retarget/
// own_skeleton.h, retarget_character.h; issue 29 item 1), on a small game-style rig: a
// root bone at the floor with a rest rotation (a Z-up armature turned to Y up), the hips
// above it with an animated translation, IK foot bones and a pole target parented to the
// root (no vertices), a cylinder mesh. The clip goes through BVH in centimetres (another
// unit, rest rotations folded into the channels) and back; renamed joints with a full
// joint map are the same skeleton; a rig with one bone 1 % longer is not.
#include "problems/retarget/own_skeleton.h"

#include <cmath>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/bvh_writer.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
#include "problems/retarget/retarget_character.h"
#include "problems/retarget/synthetic_skinned_character.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

// Z up inside the armature (as Blender exports it), turned to Y up by the root's rest
// rotation. `longer_shin` lengthens the left shin by that factor.
Skeleton MakeGameRig(const std::string& prefix = "", double longer_shin = 1.0) {
  struct J {
    const char* name;
    const char* parent;
    double x, y, z;
  };
  const J joints[] = {
      {"Root", "", 0, 0, 0},
      {"Hips", "Root", 0, 0, 0.95},
      {"Spine", "Hips", 0, 0.01, 0.2},
      {"Chest", "Spine", 0, 0, 0.25},
      {"Neck", "Chest", 0, 0, 0.2},
      {"Head", "Neck", 0, 0.02, 0.1},
      {"UpperArm.L", "Chest", 0.2, 0, 0.15},
      {"LowerArm.L", "UpperArm.L", 0.28, 0, 0},
      {"Hand.L", "LowerArm.L", 0.25, 0, 0},
      {"UpperArm.R", "Chest", -0.2, 0, 0.15},
      {"LowerArm.R", "UpperArm.R", -0.28, 0, 0},
      {"Hand.R", "LowerArm.R", -0.25, 0, 0},
      {"UpperLeg.L", "Hips", 0.1, 0, -0.05},
      {"LowerLeg.L", "UpperLeg.L", 0, 0.01, -0.42 * longer_shin},
      {"Foot.L", "LowerLeg.L", 0, 0, -0.4},
      {"UpperLeg.R", "Hips", -0.1, 0, -0.05},
      {"LowerLeg.R", "UpperLeg.R", 0, 0.01, -0.42},
      {"Foot.R", "LowerLeg.R", 0, 0, -0.4},
      {"FootIK.L", "Root", 0.1, 0, 0.08},
      {"FootIK.R", "Root", -0.1, 0, 0.08},
      {"PoleTarget.L", "Root", 0.1, -0.5, 0.5},
  };
  std::vector<JointSpec> specs;
  for (const J& j : joints) {
    JointSpec spec;
    spec.name = prefix + j.name;
    for (size_t p = 0; p < specs.size(); ++p) {
      if (specs[p].name == prefix + j.parent) spec.parent = static_cast<int>(p);
    }
    spec.offset = Eigen::Vector3d(j.x, j.y, j.z);
    specs.push_back(spec);
  }
  specs[0].rest_rotation = Eigen::Quaterniond(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()));
  Skeleton skeleton;
  EXPECT_TRUE(Skeleton::Create(specs, {{"Head_End", 5, {0, 0, 0.2}}}, Metres(), &skeleton).ok());
  return skeleton;
}

// Smooth random rotations of every joint, the root walking on the floor, the hips
// bobbing and swaying relative to it, the IK bones sliding.
Motion MakeGameClip(const Skeleton& skeleton, int frames) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const int nj = skeleton.num_joints();
  std::vector<Eigen::Vector3d> amplitude(nj), phase(nj);
  for (int j = 0; j < nj; ++j) {
    amplitude[j] = 0.6 * Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng));
    phase[j] = 3.0 * Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng));
  }
  Motion motion;
  motion.frame_rate = 30.0;
  for (int f = 0; f < frames; ++f) {
    const double t = f / 30.0;
    Pose pose = RestPose(skeleton);
    for (int j = 0; j < nj; ++j) {
      Eigen::Vector3d angles;
      for (int k = 0; k < 3; ++k) angles[k] = amplitude[j][k] * std::sin(4.0 * t + phase[j][k]);
      pose.rotations[j] = Eigen::AngleAxisd(angles.norm(), angles.norm() > 0 ? angles.normalized() : Eigen::Vector3d::UnitX());
    }
    pose.translations[0] = Eigen::Vector3d(0.3 * t, 0.0, 1.2 * t);
    const int hips = skeleton.FindJoint(skeleton.name(0).substr(0, skeleton.name(0).size() - 4) + "Hips");
    pose.translations[hips] += Eigen::Vector3d(0.05 * std::sin(6 * t), 0.02 * t, -0.1 * std::abs(std::sin(3 * t)));
    for (int j = 0; j < nj; ++j) {
      if (skeleton.name(j).find("FootIK") != std::string::npos) pose.translations[j] += Eigen::Vector3d(0, 0.2 * t, 0);
    }
    motion.frames.push_back(pose);
  }
  return motion;
}

struct Trip {
  double max_error = 0.0;  // Fraction of the target's height.
  CharacterRetargetResult result;
};

// `clip` on `skeleton` -> BVH in cm (12 digits) -> retarget onto `target` (+ its mesh).
void RoundTrip(const Skeleton& skeleton, const Motion& clip, const Skeleton& target,
               const std::vector<std::pair<std::string, std::string>>& joint_map, Trip* trip) {
  const std::string bvh = testing::TempPath("clip.bvh");
  BvhWriteOptions write;
  write.scale = 100.0;
  write.precision = 12;
  ASSERT_TRUE(WriteBvh(bvh, skeleton, clip, write).ok());
  Skeleton source;
  Motion motion;
  ASSERT_TRUE(ReadMotionFile(bvh, MotionFileOptions(), &source, &motion).ok());
  const SkinnedMesh mesh = MakeCylinderCharacter(target);
  RetargetCharacter source_view, target_view;
  source_view.skeleton = &source;
  target_view.skeleton = &target;
  target_view.mesh = &mesh;
  CharacterRetargetOptions options;
  options.setup.subsample.ratio = 4;
  options.joint_map = joint_map;
  const Status status = RetargetMotionOntoCharacter(source_view, motion, target_view, options, &trip->result);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(trip->result.clip.motion.num_frames(), clip.num_frames());
  const std::vector<Vector3dVector> truth = ClipJointPositions(target, clip);
  const std::vector<Vector3dVector> got = ClipJointPositions(target, trip->result.clip.motion);
  for (int f = 0; f < clip.num_frames(); ++f) {
    for (int j = 0; j < target.num_joints(); ++j) {
      trip->max_error = std::max(trip->max_error, (truth[f][j] - got[f][j]).norm() / trip->result.setup.target_frame.height);
    }
  }
}

TEST(OwnSkeletonTest, RecognisesTheSameSkeletonUpToUnits) {
  const Skeleton rig = MakeGameRig();
  std::vector<JointSpec> specs;
  for (int j = 0; j < rig.num_joints(); ++j) {
    specs.push_back(rig.joint(j));
    specs.back().offset *= 100.0;
    specs.back().rest_rotation = Eigen::Quaterniond::Identity();  // As BVH has it.
  }
  Skeleton centimetres;
  ASSERT_TRUE(Skeleton::Create(specs, {}, Centimetres(), &centimetres).ok());
  JointMap map;
  ASSERT_TRUE(BuildJointMap(centimetres, rig, {}, &map).ok());
  double scale = 0.0;
  EXPECT_TRUE(IsSameSkeleton(centimetres, rig, map, &scale));
  EXPECT_NEAR(scale, 0.01, 1e-12);

  const Skeleton longer = MakeGameRig("", 1.01);
  ASSERT_TRUE(BuildJointMap(centimetres, longer, {}, &map).ok());
  EXPECT_FALSE(IsSameSkeleton(centimetres, longer, map, &scale));
  // A joint left out of the map.
  ASSERT_TRUE(BuildJointMap(centimetres, rig, {}, &map).ok());
  map.source_of_target[map.target_of_source[3]] = -1;
  map.target_of_source[3] = -1;
  EXPECT_FALSE(IsSameSkeleton(centimetres, rig, map, &scale));
}

TEST(OwnSkeletonTest, GameRigRoundTripsExactlyThroughBvh) {
  const Skeleton rig = MakeGameRig();
  const Motion clip = MakeGameClip(rig, 40);
  Trip trip;
  RoundTrip(rig, clip, rig, {}, &trip);
  if (HasFatalFailure()) return;
  EXPECT_TRUE(trip.result.own_skeleton);
  EXPECT_TRUE(trip.result.plant_joints.empty());
  // 12 digits in the file: what is left is rounding (measured 1e-12).
  EXPECT_LT(trip.max_error, 1e-9);
  bool noted = false;
  for (const std::string& note : trip.result.notes) noted |= note.find("own skeleton") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(OwnSkeletonTest, RenamedJointsWithAJointMapRoundTripExactly) {
  const Skeleton rig = MakeGameRig();
  const Skeleton renamed = MakeGameRig("bone_");
  std::vector<std::pair<std::string, std::string>> joint_map;
  for (int j = 0; j < rig.num_joints(); ++j) joint_map.emplace_back(rig.name(j), renamed.name(j));
  Trip trip;
  // The clip is on `rig` (source names), the target is `renamed`.
  RoundTrip(rig, MakeGameClip(rig, 20), renamed, joint_map, &trip);
  if (HasFatalFailure()) return;
  EXPECT_TRUE(trip.result.own_skeleton);
  EXPECT_LT(trip.max_error, 1e-9);
}

TEST(OwnSkeletonTest, ADifferentRigIsSolvedNotCopied) {
  const Skeleton rig = MakeGameRig();
  const Skeleton longer = MakeGameRig("", 1.01);
  Trip trip;
  RoundTrip(rig, MakeGameClip(rig, 10), longer, {}, &trip);
  if (HasFatalFailure()) return;
  EXPECT_FALSE(trip.result.own_skeleton);
  for (const std::string& note : trip.result.notes) EXPECT_THAT(note, ::testing::Not(HasSubstr("own skeleton")));
}

}  // namespace
}  // namespace mocapsolve
