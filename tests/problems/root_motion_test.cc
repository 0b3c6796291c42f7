// Game-engine root conventions (problems/retarget/root_motion.h) on a small game rig: a
// root bone at the floor with a rest rotation (a Z-up armature turned to Y up), the hips
// above it walking and turning (60 degrees over 3 s) with a lateral sway, an IK foot bone
// under the root held still in the world (a planted foot), a cylinder mesh. In each mode:
// the root bone's track, the planted foot (skate) and the joints' heights (penetration).
#include "problems/retarget/root_motion.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "problems/retarget/retarget_character.h"
#include "problems/retarget/synthetic_skinned_character.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

const Eigen::Quaterniond kZUpToYUp(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()));
constexpr double kSway = 0.04;  // Metres, at 2 Hz.

// `with_root_bone`: Root (floor) -> Hips; else the hips are the root (Mixamo-like).
Skeleton MakeRig(bool with_root_bone) {
  struct J {
    const char* name;
    const char* parent;
    double x, y, z;  // Armature frame: Z up, -Y forward.
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
      {"LowerLeg.L", "UpperLeg.L", 0, 0.01, -0.42},
      {"Foot.L", "LowerLeg.L", 0, 0, -0.4},
      {"UpperLeg.R", "Hips", -0.1, 0, -0.05},
      {"LowerLeg.R", "UpperLeg.R", 0, 0.01, -0.42},
      {"Foot.R", "LowerLeg.R", 0, 0, -0.4},
      {"FootIK.L", "Root", 0.1, 0, 0.08},
  };
  std::vector<JointSpec> specs;
  for (const J& j : joints) {
    if (!with_root_bone && std::string(j.name).find("Root") != std::string::npos) continue;
    if (!with_root_bone && std::string(j.name) == "FootIK.L") continue;
    JointSpec spec;
    spec.name = j.name;
    for (size_t p = 0; p < specs.size(); ++p) {
      if (specs[p].name == j.parent) spec.parent = static_cast<int>(p);
    }
    spec.offset = with_root_bone || specs.size() > 0 ? Eigen::Vector3d(j.x, j.y, j.z) : Eigen::Vector3d(0, 0, 0.95);
    specs.push_back(spec);
  }
  specs[0].rest_rotation = kZUpToYUp;
  Skeleton skeleton;
  EXPECT_TRUE(Skeleton::Create(specs, {{"Head_End", 5, {0, 0, 0.2}}}, Metres(), &skeleton).ok());
  return skeleton;
}

double Heading(double t) { return M_PI / 3.0 * t / 3.0; }  // 0 -> 60 degrees over 3 s.

// The hips walk at 1.2 m/s along their heading, sway sideways and bob; the legs and arms
// swing; the IK foot stays where it is in the world (the root bone does not move).
Motion MakeWalk(const Skeleton& skeleton, std::vector<Eigen::Vector3d>* path = nullptr) {
  Motion motion;
  motion.frame_rate = 30.0;
  const int hips = skeleton.FindJoint("Hips");
  const Eigen::Quaterniond root_world = skeleton.rest_rotation(0);
  Eigen::Vector3d ground = Eigen::Vector3d::Zero();
  for (int f = 0; f < 90; ++f) {
    const double t = f / 30.0, h = Heading(t);
    const Eigen::Vector3d forward(std::sin(h), 0, std::cos(h)), side(std::cos(h), 0, -std::sin(h));
    if (f > 0) ground += 1.2 / 30.0 * forward;
    if (path != nullptr) path->push_back(ground);
    Pose pose = RestPose(skeleton);
    const Eigen::Vector3d world =
        ground + kSway * std::sin(4 * M_PI * t) * side + Eigen::Vector3d(0, 0.95 + 0.02 * std::cos(8 * M_PI * t), 0);
    const Eigen::Quaterniond yaw(Eigen::AngleAxisd(h + 0.1 * std::sin(4 * M_PI * t), Eigen::Vector3d::UnitY()));
    if (hips == 0) {
      pose.translations[0] = world;
      pose.rotations[0] = root_world.conjugate() * yaw * root_world;
    } else {
      pose.translations[hips] = root_world.conjugate() * world;  // Root at rest at the origin.
      pose.rotations[hips] = root_world.conjugate() * yaw * root_world;
    }
    for (const char* leg : {"UpperLeg.L", "UpperLeg.R"}) {
      const double sign = std::string(leg).back() == 'L' ? 1.0 : -1.0;
      pose.rotations[skeleton.FindJoint(leg)] =
          Eigen::AngleAxisd(sign * 0.5 * std::sin(2 * M_PI * t), Eigen::Vector3d::UnitX());
    }
    pose.rotations[skeleton.FindJoint("UpperArm.L")] =
        Eigen::AngleAxisd(0.3 * std::sin(2 * M_PI * t), Eigen::Vector3d::UnitY());
    motion.frames.push_back(pose);
  }
  return motion;
}

struct World {
  std::vector<Vector3dVector> positions;
  std::vector<QuaternionVector> rotations;
};

World WorldFrames(const Skeleton& skeleton, const Motion& motion) {
  World world;
  FkData fk(skeleton);
  for (const Pose& pose : motion.frames) {
    ForwardKinematics(skeleton, pose, &fk);
    world.positions.push_back(fk.world_positions);
    world.rotations.push_back(fk.world_rotations);
  }
  return world;
}

TEST(RootMotionTest, ParsesTheModes) {
  RootMotionMode mode;
  EXPECT_TRUE(ParseRootMotionMode("root_bone", &mode));
  EXPECT_EQ(mode, RootMotionMode::kRootBone);
  EXPECT_TRUE(ParseRootMotionMode("in_place", &mode));
  EXPECT_STREQ(RootMotionModeName(mode), "in_place");
  EXPECT_FALSE(ParseRootMotionMode("root", &mode));
}

TEST(RootMotionTest, TheHipsOfARigWithIkBonesUnderItsRoot) {
  const Skeleton rig = MakeRig(true);
  EXPECT_EQ(rig.name(FirstBranchingJoint(rig)), "Hips");
  const Skeleton no_root_bone = MakeRig(false);
  EXPECT_EQ(no_root_bone.name(FirstBranchingJoint(no_root_bone)), "Hips");
}

TEST(RootMotionTest, KeepChangesNothing) {
  const Skeleton rig = MakeRig(true);
  const Motion walk = MakeWalk(rig);
  Motion motion = walk;
  RootMotionResult result;
  ASSERT_TRUE(ApplyRootMotion(rig, 1, RootMotionOptions(), &motion, &result).ok());
  for (int f = 0; f < walk.num_frames(); ++f) {
    for (int j = 0; j < rig.num_joints(); ++j) {
      EXPECT_EQ(motion.frames[f].translations[j], walk.frames[f].translations[j]);
    }
  }
  EXPECT_TRUE(result.note.empty());
}

TEST(RootMotionTest, RootBoneCarriesTheSmoothedTrackAndNothingElseMoves) {
  const Skeleton rig = MakeRig(true);
  std::vector<Eigen::Vector3d> path;  // The hips' ground path without the sway.
  const Motion walk = MakeWalk(rig, &path);
  const World before = WorldFrames(rig, walk);
  Motion motion = walk;
  RootMotionOptions options;
  options.mode = RootMotionMode::kRootBone;
  RootMotionResult result;
  ASSERT_TRUE(ApplyRootMotion(rig, rig.FindJoint("Hips"), options, &motion, &result).ok());
  EXPECT_EQ(result.root_bone, 0);
  EXPECT_THAT(result.note, HasSubstr("carried by the root bone 'Root'"));
  const World after = WorldFrames(rig, motion);
  const int hips = rig.FindJoint("Hips");
  for (int f = 0; f < walk.num_frames(); ++f) {
    // Every joint below the root where it was (planted IK foot included: no skate, same heights).
    for (int j = 1; j < rig.num_joints(); ++j) {
      EXPECT_LT((after.positions[f][j] - before.positions[f][j]).norm(), 1e-12);
      EXPECT_LT(after.rotations[f][j].angularDistance(before.rotations[f][j]), 1e-12);
    }
    // The root bone: on the floor, under the hips within the sway, facing the heading.
    const Eigen::Vector3d root = after.positions[f][0],
                          hips_ground(before.positions[f][hips].x(), 0, before.positions[f][hips].z());
    EXPECT_NEAR(root.y(), 0.0, 1e-12);
    EXPECT_LT((root - hips_ground).norm(), kSway + 0.01) << "frame " << f;
    const Eigen::Quaterniond turn = after.rotations[f][0] * rig.rest_rotation(0).conjugate();
    // The yaw wobble (0.1 rad at 2 Hz) smoothed away inside; the end samples are kept.
    const bool inside = f >= 10 && f < 80;
    EXPECT_NEAR(Eigen::AngleAxisd(turn).angle(), Heading(f / 30.0), inside ? 0.03 : 0.13) << "frame " << f;
    EXPECT_NEAR(std::abs(Eigen::AngleAxisd(turn).axis().y()), 1.0, 1e-9);
  }
  // Smoothed: the root's lateral sway about the hips' path is a fraction of the hips'
  // (2 Hz under a Gaussian of 0.15 s: exp(-2 pi^2 0.15^2 2^2) = 0.17), plus the inward
  // cut of a smoothed curve (radius 3.4 m: (0.15 s * 1.2 m/s)^2 / (2 * 3.4 m) = 0.0047 m).
  double sway = 0.0;
  for (int f = 15; f < 75; ++f) {
    const double h = Heading(f / 30.0);
    const Eigen::Vector3d side(std::cos(h), 0, -std::sin(h));
    sway = std::max(sway, std::abs((after.positions[f][0] - path[f]).dot(side)));
  }
  EXPECT_LT(sway, 0.35 * kSway);
  EXPECT_NEAR(result.track_length, 1.2 * 89 / 30.0, 0.05);
}

TEST(RootMotionTest, InPlaceRemovesTheTrackKeepsHeadingAndHeightsAndTheRootBoneAtRest) {
  const Skeleton rig = MakeRig(true);
  const Motion walk = MakeWalk(rig);
  const World before = WorldFrames(rig, walk);
  Motion motion = walk;
  RootMotionOptions options;
  options.mode = RootMotionMode::kInPlace;
  RootMotionResult result;
  ASSERT_TRUE(ApplyRootMotion(rig, rig.FindJoint("Hips"), options, &motion, &result).ok());
  const World after = WorldFrames(rig, motion);
  const int hips = rig.FindJoint("Hips");
  for (int f = 0; f < walk.num_frames(); ++f) {
    const Eigen::Vector3d shift = result.track[f] - result.track[0];
    EXPECT_NEAR(shift.y(), 0.0, 1e-15);
    for (int j = 1; j < rig.num_joints(); ++j) {
      // Shifted rigidly: heights (penetration) and orientations (heading) kept; in the
      // frame that moves with the removed track the planted IK foot does not skate.
      EXPECT_LT((after.positions[f][j] + shift - before.positions[f][j]).norm(), 1e-12);
      EXPECT_LT(after.rotations[f][j].angularDistance(before.rotations[f][j]), 1e-12);
    }
    EXPECT_LT((after.positions[f][0] - before.positions[0][0]).norm(), 1e-12);  // Root bone at rest.
    const Eigen::Vector3d offset = after.positions[f][hips] - before.positions[0][hips];
    EXPECT_LT(std::hypot(offset.x(), offset.z()), kSway + 0.01) << "frame " << f;  // On the spot.
  }
}

TEST(RootMotionTest, InPlaceWithoutARootBoneMovesTheHips) {
  const Skeleton rig = MakeRig(false);
  Motion motion = MakeWalk(rig);
  const World before = WorldFrames(rig, motion);
  RootMotionOptions options;
  options.mode = RootMotionMode::kInPlace;
  RootMotionResult result;
  ASSERT_TRUE(ApplyRootMotion(rig, 0, options, &motion, &result).ok());
  EXPECT_EQ(result.root_bone, -1);
  const World after = WorldFrames(rig, motion);
  const Eigen::Vector3d travelled = after.positions.back()[0] - after.positions[0][0];
  EXPECT_LT(std::hypot(travelled.x(), travelled.z()), kSway + 0.01);
  EXPECT_NEAR(after.positions[45][0].y(), before.positions[45][0].y(), 1e-12);
}

TEST(RootMotionTest, RootBoneOnARigWhoseRootIsTheHipsIsAnError) {
  const Skeleton rig = MakeRig(false);
  Motion motion = MakeWalk(rig);
  RootMotionOptions options;
  options.mode = RootMotionMode::kRootBone;
  RootMotionResult result;
  const Status status = ApplyRootMotion(rig, 0, options, &motion, &result);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("no root bone above its hips ('Hips'"));
}

// Through the retarget (the rig's own clip onto the rig: the exact transfer, then the step).
TEST(RootMotionTest, TheRetargetAppliesTheModeAfterItsQualityFigures) {
  const Skeleton rig = MakeRig(true);
  const Motion walk = MakeWalk(rig);
  const SkinnedMesh mesh = MakeCylinderCharacter(rig);
  RetargetCharacter source, target;
  source.skeleton = &rig;
  target.skeleton = &rig;
  target.mesh = &mesh;
  CharacterRetargetResult keep, root_bone;
  CharacterRetargetOptions options;
  options.setup.subsample.ratio = 4;
  ASSERT_TRUE(RetargetMotionOntoCharacter(source, walk, target, options, &keep).ok());
  options.root_motion.mode = RootMotionMode::kRootBone;
  ASSERT_TRUE(RetargetMotionOntoCharacter(source, walk, target, options, &root_bone).ok());
  EXPECT_EQ(root_bone.root_motion.hips, rig.FindJoint("Hips"));
  bool noted = false;
  for (const std::string& note : root_bone.notes) noted |= note.find("root motion root_bone") != std::string::npos;
  EXPECT_TRUE(noted);
  EXPECT_EQ(root_bone.quality.penetration_cm, keep.quality.penetration_cm);
  const World a = WorldFrames(rig, keep.clip.motion), b = WorldFrames(rig, root_bone.clip.motion);
  EXPECT_LT((a.positions.back()[0] - a.positions[0][0]).norm(), 1e-9);  // keep: the root stays.
  EXPECT_GT((b.positions.back()[0] - b.positions[0][0]).norm(), 3.0);   // root_bone: it walks.
  EXPECT_LT((a.positions[60][14] - b.positions[60][14]).norm(), 1e-9);  // Foot.L where it was.
}

}  // namespace
}  // namespace mocapsolve
