#include "io/asf_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// A small skeleton with a branch (root -> hip -> thigh -> shin, root -> spine), bones
// without dofs, non-trivial axes, limits spread over lines and on one line.
const char kTinyAsf[] = R"(# AST/ASF test fixture
# a second comment line
:version 1.10
:name tiny
:units
  mass 1.0
  length 0.45
  angle deg
:documentation
   free text, even 'begin' or 'end' or (1 2)
:root
   order TX TY TZ RX RY RZ
   axis XYZ
   position 0 0 0
   orientation 0 0 0
:bonedata
  begin
     id 1
     name hip
     direction 0.6 -0.8 0
     length 2.5
     axis 0 0 0 XYZ
  end
  begin
     id 2
     name thigh
     direction 0.34202 -0.939693 0
     length 7
     axis 0 0 20 XYZ
    dof rx ry rz
    limits (-160.0 20.0)
           (-70.0 70.0)
           (-60.0 70.0)
  end
  begin
     id 3
     name shin
     direction 0.34202 -0.939693 0
     length 7.5
     axis 10 -5 20 XYZ
    dof rx
    limits (-10.0 170.0)
  end
  begin
     id 4
     name spine
     direction 0 1 0.1
     length 2
     axis 180 -30 -90 XYZ
    dof rz rx
    limits (-inf inf) ( -30 30 )
    bodymass 3.0
    cofmass 1.0
  end
:hierarchy
  begin
    root hip spine
    hip thigh
    thigh shin
  end
)";

Eigen::Matrix3d Rot(int axis, double deg) {
  return Eigen::AngleAxisd(DegToRad(deg), Eigen::Vector3d::Unit(axis)).toRotationMatrix();
}

// Bone tails at rest, straight from the file's directions and lengths:
// tail_b = tail_parent + d_b L_b (root children start at the root position).
std::vector<Eigen::Vector3d> RestTails(const Skeleton& skeleton, const AsfInfo& info) {
  std::vector<Eigen::Vector3d> tail(skeleton.num_joints(), info.root_position);
  for (int j = 1; j < skeleton.num_joints(); ++j) {
    const AsfBone& bone = info.bones[info.bone_of_joint[j]];
    tail[j] = tail[skeleton.parent(j)] + bone.direction * bone.length;
  }
  return tail;
}

// At rest every joint sits at its bone's start (= parent's tail), every end site at its
// leaf bone's tail, and every joint frame is the bone's axis rotation C_b in the world.
void ExpectRestPoseMatchesBones(const Skeleton& skeleton, const AsfInfo& info) {
  const std::vector<Eigen::Vector3d> tail = RestTails(skeleton, info);
  FkData fk(skeleton);
  ForwardKinematics(skeleton, RestPose(skeleton), &fk);
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    const Eigen::Vector3d start = j == 0 ? info.root_position : tail[skeleton.parent(j)];
    EXPECT_LT((fk.world_positions[j] - start).norm(), 1e-12) << skeleton.name(j);
    const Eigen::Quaterniond c =
        j == 0 ? info.root_axis_rotation : info.bones[info.bone_of_joint[j]].axis_rotation;
    EXPECT_LT(AngularDistance(fk.world_rotations[j], c), 1e-12) << skeleton.name(j);
  }
  const Vector3dVector sites = EndSitePositions(skeleton, fk);
  for (size_t s = 0; s < sites.size(); ++s) {
    const int j = skeleton.end_sites()[s].parent;
    EXPECT_EQ(skeleton.end_sites()[s].name, skeleton.name(j) + "_End");
    EXPECT_LT((sites[s] - tail[j]).norm(), 1e-12) << skeleton.end_sites()[s].name;
  }
}

TEST(AsfReader, TinySkeletonStructure) {
  Skeleton skeleton;
  AsfInfo info;
  const Status status = ParseAsf(kTinyAsf, "tiny.asf", &skeleton, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(info.version, "1.10");
  EXPECT_EQ(info.name, "tiny");
  EXPECT_DOUBLE_EQ(info.length_scale, 0.45);
  EXPECT_TRUE(info.angles_in_degrees);
  EXPECT_NEAR(skeleton.unit().metres_per_unit, 0.0254 / 0.45, 1e-15);

  // Preorder, children in the listed order.
  ASSERT_EQ(skeleton.num_joints(), 5);
  const std::vector<std::string> names = {"root", "hip", "thigh", "shin", "spine"};
  const std::vector<int> parents = {-1, 0, 1, 2, 0};
  for (int j = 0; j < 5; ++j) {
    EXPECT_EQ(skeleton.name(j), names[j]);
    EXPECT_EQ(skeleton.parent(j), parents[j]);
  }
  // Bones stay in file order; they point at their joints and back.
  ASSERT_EQ(info.bones.size(), 4u);
  EXPECT_EQ(info.bones[3].name, "spine");
  EXPECT_EQ(info.bones[3].joint, 4);
  EXPECT_EQ(info.bones[3].parent_joint, 0);
  EXPECT_EQ(info.bones[3].line, 44);
  EXPECT_EQ(info.bone_of_joint, (std::vector<int>{-1, 0, 1, 2, 3}));
  EXPECT_EQ(info.FindBone("shin"), 2);
  EXPECT_EQ(info.FindBone("root"), -1);

  // Channels: root 'order', bones their dofs in file order, none without dofs.
  EXPECT_EQ(skeleton.joint(0).channels,
            (std::vector<Channel>{Channel::kXposition, Channel::kYposition, Channel::kZposition,
                                  Channel::kXrotation, Channel::kYrotation, Channel::kZrotation}));
  EXPECT_TRUE(skeleton.has_translation_channels(0));
  EXPECT_TRUE(skeleton.joint(1).channels.empty());
  EXPECT_EQ(skeleton.joint(4).channels,
            (std::vector<Channel>{Channel::kZrotation, Channel::kXrotation}));

  // Dofs and limits in degrees, in the file's order.
  const AsfBone& thigh = info.bones[1];
  ASSERT_EQ(thigh.dofs.size(), 3u);
  EXPECT_EQ(thigh.dofs[1].dof, AcclaimDof::kRy);
  EXPECT_EQ(thigh.dofs[2].lower_deg, -60.0);
  EXPECT_EQ(thigh.dofs[2].upper_deg, 70.0);
  const AsfBone& spine = info.bones[3];
  ASSERT_EQ(spine.dofs.size(), 2u);
  EXPECT_EQ(spine.dofs[0].dof, AcclaimDof::kRz);
  EXPECT_TRUE(std::isinf(spine.dofs[0].lower_deg) && spine.dofs[0].lower_deg < 0);
  EXPECT_TRUE(std::isinf(spine.dofs[0].upper_deg) && spine.dofs[0].upper_deg > 0);
  EXPECT_EQ(spine.dofs[1].lower_deg, -30.0);
  EXPECT_TRUE(info.bones[0].dofs.empty());
  EXPECT_EQ(info.root_order.size(), 6u);
  EXPECT_EQ(info.root_order[3].dof, AcclaimDof::kRx);

  // The direction is normalized; axis kept as written.
  EXPECT_NEAR(spine.direction.norm(), 1.0, 1e-15);
  EXPECT_EQ(spine.axis_deg, Eigen::Vector3d(180, -30, -90));
  EXPECT_EQ(spine.axis_order, "XYZ");

  // Leaves get end sites.
  ASSERT_EQ(skeleton.end_sites().size(), 2u);
  EXPECT_EQ(skeleton.end_sites()[0].name, "shin_End");
  EXPECT_EQ(skeleton.end_sites()[1].name, "spine_End");
  ExpectRestPoseMatchesBones(skeleton, info);
}

TEST(AsfReader, MappingFormulas) {
  Skeleton skeleton;
  AsfInfo info;
  ASSERT_TRUE(ParseAsf(kTinyAsf, "tiny.asf", &skeleton, &info).ok());
  // rest_rotation = C_parent^-1 C_b, offset = C_parent^-1 d_parent L_parent (zero below
  // the root), end site = C_b^-1 d_b L_b.
  const AsfBone& thigh = info.bones[1];
  const AsfBone& shin = info.bones[2];
  EXPECT_LT(AngularDistance(skeleton.rest_rotation(3),
                            thigh.axis_rotation.conjugate() * shin.axis_rotation),
            1e-14);
  EXPECT_LT((skeleton.offset(3) -
             thigh.axis_rotation.conjugate() * (thigh.direction * thigh.length))
                .norm(),
            1e-14);
  EXPECT_EQ(skeleton.offset(1), Eigen::Vector3d::Zero());
  EXPECT_EQ(skeleton.offset(4), Eigen::Vector3d::Zero());
  EXPECT_LT((skeleton.end_sites()[0].offset -
             shin.axis_rotation.conjugate() * (shin.direction * shin.length))
                .norm(),
            1e-14);
}

TEST(AsfReader, AxisRotationAppliesAnglesInTheWrittenOrder) {
  // "axis 10 20 30 XYZ" is C = Rz(30) Ry(20) Rx(10): x first.
  const Eigen::Vector3d xyz(10, 20, 30);
  const Eigen::Vector3d rad = xyz * (kPi / 180.0);
  EXPECT_TRUE(AcclaimAxisRotation(rad, "XYZ").toRotationMatrix().isApprox(
      Rot(2, 30) * Rot(1, 20) * Rot(0, 10), 1e-14));
  // The angles stay tied to x, y, z whatever the order.
  EXPECT_TRUE(AcclaimAxisRotation(rad, "ZYX").toRotationMatrix().isApprox(
      Rot(0, 10) * Rot(1, 20) * Rot(2, 30), 1e-14));
  EXPECT_TRUE(AcclaimAxisRotation(rad, "YZX").toRotationMatrix().isApprox(
      Rot(0, 10) * Rot(2, 30) * Rot(1, 20), 1e-14));
  // Dof lists: "rz rx" with (a, b) is Rx(b) Rz(a).
  const int axes[2] = {2, 0};
  const double angles[2] = {DegToRad(40), DegToRad(-25)};
  EXPECT_TRUE(AcclaimEulerRotation(2, axes, angles).toRotationMatrix().isApprox(
      Rot(0, -25) * Rot(2, 40), 1e-14));
  EXPECT_TRUE(AcclaimEulerRotation(0, axes, angles).isApprox(Eigen::Quaterniond::Identity()));
  // Same as QuaternionFromEuler with the order (and the angles) reversed.
  EXPECT_LT(AngularDistance(AcclaimAxisRotation(rad, "XYZ"),
                            QuaternionFromEuler(Eigen::Vector3d(rad.z(), rad.y(), rad.x()),
                                                EulerOrder::kZYX)),
            1e-14);
}

TEST(AsfReader, RadiansRootOrientationCrlfAndOneLineLimits) {
  std::string text = kTinyAsf;
  auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("angle deg", "angle rad");
  replace("axis 0 0 20 XYZ", "axis 0.1 -0.2 0.3 ZYX");
  replace("axis XYZ\n   position 0 0 0\n   orientation 0 0 0",
          "axis ZXY\n   position 1 2 3\n   orientation 0.5 0.25 -1");
  replace("limits (-160.0 20.0)\n           (-70.0 70.0)\n           (-60.0 70.0)",
          "limits (-1 0.5) (-0.5 0.5)\n (-inf 1)");
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);

  Skeleton skeleton;
  AsfInfo info;
  const Status status = ParseAsf(crlf, "rad.asf", &skeleton, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_FALSE(info.angles_in_degrees);
  // Angles are reported in degrees.
  const AsfBone& thigh = info.bones[1];
  EXPECT_NEAR(thigh.axis_deg.x(), RadToDeg(0.1), 1e-12);
  EXPECT_EQ(thigh.axis_order, "ZYX");
  EXPECT_NEAR(thigh.dofs[0].lower_deg, RadToDeg(-1.0), 1e-12);
  EXPECT_NEAR(thigh.dofs[2].upper_deg, RadToDeg(1.0), 1e-12);
  EXPECT_TRUE(std::isinf(thigh.dofs[2].lower_deg));
  EXPECT_TRUE(thigh.axis_rotation.toRotationMatrix().isApprox(
      Rot(0, RadToDeg(0.1)) * Rot(1, RadToDeg(-0.2)) * Rot(2, RadToDeg(0.3)), 1e-14));
  EXPECT_NEAR(info.root_orientation_deg.z(), RadToDeg(-1.0), 1e-12);
  EXPECT_EQ(info.root_position, Eigen::Vector3d(1, 2, 3));
  // Root: rest rotation is C_root (orientation in 'axis' order), offset its position.
  EXPECT_LT(AngularDistance(skeleton.rest_rotation(0), info.root_axis_rotation), 1e-15);
  EXPECT_TRUE(info.root_axis_rotation.toRotationMatrix().isApprox(
      Rot(1, RadToDeg(0.25)) * Rot(0, RadToDeg(0.5)) * Rot(2, RadToDeg(-1.0)), 1e-14));
  EXPECT_EQ(skeleton.offset(0), Eigen::Vector3d(1, 2, 3));
  // Positions at rest do not depend on the axes.
  ExpectRestPoseMatchesBones(skeleton, info);
}

TEST(AsfReader, SkeletonWithOnlyARoot) {
  Skeleton skeleton;
  AsfInfo info;
  const Status status = ParseAsf(":root\n order TX TY TZ RX RY RZ\n axis XYZ\n:bonedata\n",
                                 "root_only.asf", &skeleton, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(skeleton.num_joints(), 1);
  EXPECT_TRUE(skeleton.end_sites().empty());
  EXPECT_EQ(info.length_scale, 1.0);  // Default units: 1 inch per unit.
}

// Replaces the first occurrence of `from` in kTinyAsf.
std::string TinyWith(const std::string& from, const std::string& to) {
  std::string text = kTinyAsf;
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(AsfReader, ErrorsNameFileAndLine) {
  struct Case {
    std::string text;
    std::string expected;  // Prefix "t.asf:LINE: " + a part of the message.
  };
  const std::vector<Case> cases = {
      {TinyWith(":version", "version"), "t.asf:3: expected a ':' keyword"},
      {TinyWith("angle deg", "angle grad"), "t.asf:8: angle unit"},
      {TinyWith("length 0.45", "length 0"), "t.asf:7: length must be a positive number"},
      {TinyWith("order TX TY TZ RX RY RZ", "order TX TY TW"), "t.asf:12: root order entries"},
      {TinyWith("   order TX TY TZ RX RY RZ\n", ""), "t.asf:11: :root has no 'order'"},
      {TinyWith("position 0 0 0", "position 0 0"), "t.asf:14: expected 'position x y z'"},
      {TinyWith("     id 1\n", "     id 1\n  begin\n"), "t.asf:19: 'begin' before 'end'"},
      {TinyWith("name hip", "name root"), "t.asf:19: a bone cannot be named 'root'"},
      {TinyWith("name shin", "name thigh"), "t.asf:37: bone name 'thigh' already used at line 24"},
      {TinyWith("     direction 0.6 -0.8 0\n", ""), "t.asf:17: bone 'hip' has no 'direction'"},
      {TinyWith("length 2.5", "length -1"), "t.asf:21: expected 'length <non-negative"},
      {TinyWith("direction 0.6 -0.8 0", "direction 0 0 0"), "t.asf:17: bone 'hip' has a zero"},
      {TinyWith("axis 0 0 20 XYZ", "axis 0 0 20 XYX"), "t.asf:29: expected 'axis x y z ORDER'"},
      {TinyWith("direction 0.6 -0.8 0", "direction 0.6 -0.8 1e999"), "t.asf:20: bad number"},
      {TinyWith("dof rx ry rz", "dof rx ry rx"), "t.asf:30: repeated dof 'rx'"},
      {TinyWith("dof rx ry rz", "dof rx ry l"), "t.asf:30: unsupported dof 'l'"},
      {TinyWith("dof rx ry rz", "dof rx ry tz"), "t.asf:30: unsupported dof 'tz'"},
      {TinyWith("(-70.0 70.0)", "(-70.0 70.0) (1 2)"), "t.asf:33: more limits than dofs"},
      {TinyWith("(-70.0 70.0)", "(-70.0 70.0) (1 2) (3 4)"), "t.asf:32: more limits than dofs"},
      {TinyWith("(-70.0 70.0)", "(-70.0 nan)"), "t.asf:32: bad limits"},
      {TinyWith("(-70.0 70.0)", "(-70.0 70.0"), "t.asf:32: expected limits as '(lower upper)'"},
      {TinyWith("    dof rx\n", ""), "t.asf:41: 'limits' before 'dof'"},
      {TinyWith("    bodymass 3.0", "    mass 3.0"), "t.asf:52: unknown bone entry 'mass'"},
      {TinyWith("  end\n:hierarchy", ":hierarchy"), "t.asf:54: ':hierarchy' before 'end' (bone begun at line 44)"},
      {TinyWith("    thigh shin\n  end\n", "    thigh shin\n"), "t.asf:59: missing 'end' of :hierarchy"},
      {TinyWith("    thigh shin\n", "    thigh shin\n    shin hip\n"),
       "t.asf:60: bone 'hip' already has a parent (line 57)"},
      {TinyWith("    thigh shin\n", "    thigh root\n"), "t.asf:59: 'root' cannot be a child"},
      {TinyWith("    thigh shin\n", "    shin shin\n"), "t.asf:59: bone 'shin' is its own parent"},
      {TinyWith("    thigh shin\n", ""), "t.asf:35: bone 'shin' is not a child of anything"},
      {TinyWith("    root hip spine\n    hip thigh\n", "    root spine\n    hip thigh\n    shin hip\n"),
       "t.asf:17: bone 'hip' is not connected to the root"},
      {std::string(kTinyAsf) + "  extra\n", "t.asf:61: unexpected 'extra' after"},
      {TinyWith(":hierarchy", ":units\n mass 1\n:hierarchy"), "t.asf:55: repeated :units (first at line 5)"},
      {std::string(kTinyAsf).substr(0, std::string(kTinyAsf).find(":hierarchy")),
       "t.asf:54: no :hierarchy section"},
      {"", "t.asf:1: no :root section"},
      {":root\n order TX\n", "t.asf:2: no :bonedata section"},
  };
  for (const Case& c : cases) {
    Skeleton skeleton;
    AsfInfo info;
    const Status status = ParseAsf(c.text, "t.asf", &skeleton, &info);
    ASSERT_FALSE(status.ok()) << c.expected;
    const std::string prefix = c.expected.substr(0, c.expected.find(": ") + 2);
    EXPECT_EQ(status.message().rfind(prefix, 0), 0u) << status.message() << "\nexpected " << c.expected;
    EXPECT_NE(status.message().find(c.expected.substr(prefix.size())), std::string::npos)
        << status.message() << "\nexpected " << c.expected;
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
  }
}

TEST(AsfReader, MissingFileAndDirectory) {
  Skeleton skeleton;
  AsfInfo info;
  Status status = ReadAsf("/nonexistent/x.asf", &skeleton, &info);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("/nonexistent/x.asf"), std::string::npos);
  status = ReadAsf(testing::SourcePath("tests/data/bad"), &skeleton, &info);
  ASSERT_FALSE(status.ok());
}

// Each tests/data/bad/bad_*.asf starts with
// "# expect-error: line N: <part of the message>".
TEST(AsfReader, BadFilesGiveOneLineErrorsWithFileAndLine) {
  const int checked = testing::CheckAnnotatedBadFiles(".asf", [](const std::string& path) {
    Skeleton skeleton;
    AsfInfo info;
    return ReadAsf(path, &skeleton, &info);
  });
  EXPECT_GE(checked, 6);
  // The good skeleton beside them (the AMC cases use it) reads.
  Skeleton skeleton;
  AsfInfo info;
  const Status status = ReadAsf(testing::SourcePath("tests/data/bad/tiny_ok.asf"), &skeleton, &info);
  EXPECT_TRUE(status.ok()) << status.message();
}

// Random damage (bytes replaced, deleted, inserted, lines cut) never crashes or hangs:
// the result is a valid skeleton or a one-line error naming the input.
TEST(AsfReader, SurvivesRandomDamage) {
  std::mt19937 rng(20240521);
  const std::string base = kTinyAsf;
  std::string alphabet = "()#:\n\r\t -.0123456789eEinfrxyzXYZ begin end root abc";
  alphabet += '\0';
  alphabet += '\xff';
  int parsed = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const std::string text = testing::RandomlyDamaged(base, alphabet, &rng);
    Skeleton skeleton;
    AsfInfo info;
    const Status status = ParseAsf(text, "fuzz.asf", &skeleton, &info);
    if (status.ok()) {
      ++parsed;
      EXPECT_EQ(info.bone_of_joint.size(), static_cast<size_t>(skeleton.num_joints()));
      EXPECT_EQ(info.bones.size() + 1, static_cast<size_t>(skeleton.num_joints()));
    } else {
      EXPECT_EQ(status.message().rfind("fuzz.asf:", 0), 0u) << status.message();
      EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
    }
  }
  EXPECT_GT(parsed, 0);  // Some damage is harmless (comments, documentation).
}

// The CMU skeletons: 30 bones + root, 7 leaves, units 1/0.45 inch, Y up.
class CmuAsfTest : public ::testing::TestWithParam<const char*> {};

TEST_P(CmuAsfTest, Reads) {
  MOCAPSOLVE_DATA_FILE(path, GetParam());
  Skeleton skeleton;
  AsfInfo info;
  const Status status = ReadAsf(path, &skeleton, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(skeleton.num_joints(), 31);
  EXPECT_EQ(info.bones.size(), 30u);
  EXPECT_EQ(skeleton.end_sites().size(), 7u);
  EXPECT_EQ(skeleton.name(0), "root");
  EXPECT_NEAR(skeleton.unit().metres_per_unit, 0.0254 / 0.45, 1e-15);
  EXPECT_EQ(info.root_order.size(), 6u);
  EXPECT_EQ(info.root_axis_order, "XYZ");

  const int lfemur = info.FindBone("lfemur");
  ASSERT_GE(lfemur, 0);
  const AsfBone& bone = info.bones[lfemur];
  EXPECT_EQ(skeleton.name(skeleton.parent(bone.joint)), "lhipjoint");
  ASSERT_EQ(bone.dofs.size(), 3u);
  EXPECT_EQ(bone.dofs[0].lower_deg, -160.0);
  EXPECT_EQ(bone.dofs[0].upper_deg, 20.0);
  EXPECT_EQ(bone.axis_deg, Eigen::Vector3d(0, 0, 20));
  const AsfBone& lhumerus = info.bones[info.FindBone("lhumerus")];
  EXPECT_EQ(lhumerus.axis_deg, Eigen::Vector3d(180, -30, -90));
  EXPECT_TRUE(info.bones[info.FindBone("lhipjoint")].dofs.empty());
  EXPECT_EQ(info.bones[info.FindBone("lwrist")].dofs.size(), 1u);
  // Standing: the head is above the root, the toes below.
  ExpectRestPoseMatchesBones(skeleton, info);
  FkData fk(skeleton);
  ForwardKinematics(skeleton, RestPose(skeleton), &fk);
  EXPECT_GT(fk.world_positions[skeleton.FindJoint("head")].y(), 8.0);
  EXPECT_LT(fk.world_positions[skeleton.FindJoint("ltoes")].y(), -10.0);
}

INSTANTIATE_TEST_SUITE_P(CmuFiles, CmuAsfTest,
                         ::testing::Values("amc/01.asf", "amc/02.asf", "amc/16.asf"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           return "subject_" + std::string(info.param).substr(4, 2);
                         });

}  // namespace
}  // namespace mocapsolve
