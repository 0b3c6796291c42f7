#include "io/amc_reader.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/asf_reader.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// root -> hip -> thigh -> shin, root -> spine; non-trivial axes everywhere, a root
// orientation, and a dof list out of x-y-z order ("rz rx").
const char kTinyAsf[] = R"(:version 1.10
:name tiny
:units
  mass 1.0
  length 0.45
  angle deg
:root
   order TX TY TZ RX RY RZ
   axis XYZ
   position 0.5 1 -2
   orientation 5 -10 15
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
  end
  begin
     id 3
     name shin
     direction 0.34202 -0.939693 0
     length 7.5
     axis 10 -5 20 XYZ
    dof rx
  end
  begin
     id 4
     name spine
     direction 0 1 0.1
     length 2
     axis 180 -30 -90 XYZ
    dof rz rx
  end
:hierarchy
  begin
    root hip spine
    hip thigh
    thigh shin
  end
)";

const char kTinyAmc[] = R"(#!OML:ASF tiny.asf
# a comment
:FULLY-SPECIFIED
:DEGREES
1
root 1 2 3 10 20 30
hip
thigh 5 -6 7
shin 45
spine 30 -20
2
spine 31 -21
shin 46
thigh 5.5 -6.5 7.5
root 1.1 2.1 3.1 11 21 31
)";

Eigen::Matrix3d Rot(int axis, double deg) {
  return Eigen::AngleAxisd(DegToRad(deg), Eigen::Vector3d::Unit(axis)).toRotationMatrix();
}

void ReadTiny(Skeleton* skeleton, AsfInfo* info) {
  const Status status = ParseAsf(kTinyAsf, "tiny.asf", skeleton, info);
  ASSERT_TRUE(status.ok()) << status.message();
}

TEST(AmcReader, TinyMotion) {
  Skeleton skeleton;
  AsfInfo info;
  ReadTiny(&skeleton, &info);
  Motion motion;
  const Status status = ParseAmc(kTinyAmc, "tiny.amc", skeleton, info, 120.0, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(motion.frame_rate, 120.0);
  ASSERT_EQ(motion.num_frames(), 2);
  EXPECT_TRUE(ValidateMotion(skeleton, motion).ok());
  const Pose& pose = motion.frames[0];
  // Root: position + TX TY TZ; RX RY RZ applied x first.
  EXPECT_LT((pose.translations[0] - Eigen::Vector3d(1.5, 3, 1)).norm(), 1e-15);
  EXPECT_TRUE(pose.rotations[0].toRotationMatrix().isApprox(Rot(2, 30) * Rot(1, 20) * Rot(0, 10),
                                                            1e-14));
  // Bones: rest offsets, dof rotations in dof order, identity without dofs.
  const int thigh = skeleton.FindJoint("thigh"), shin = skeleton.FindJoint("shin");
  const int spine = skeleton.FindJoint("spine"), hip = skeleton.FindJoint("hip");
  EXPECT_EQ(pose.translations[thigh], skeleton.offset(thigh));
  EXPECT_TRUE(pose.rotations[thigh].toRotationMatrix().isApprox(
      Rot(2, 7) * Rot(1, -6) * Rot(0, 5), 1e-14));
  EXPECT_TRUE(pose.rotations[shin].toRotationMatrix().isApprox(Rot(0, 45), 1e-14));
  EXPECT_TRUE(pose.rotations[spine].toRotationMatrix().isApprox(Rot(0, -20) * Rot(2, 30), 1e-14));
  EXPECT_TRUE(pose.rotations[hip].isApprox(Eigen::Quaterniond::Identity()));
  // Frame 2 lists the bones in another order and leaves out the dof-less hip.
  EXPECT_TRUE(motion.frames[1].rotations[shin].toRotationMatrix().isApprox(Rot(0, 46), 1e-14));
  EXPECT_LT((motion.frames[1].translations[0] - Eigen::Vector3d(1.6, 3.1, 1.1)).norm(), 1e-14);
}

TEST(AmcReader, RadiansAndDefaultAngleUnit) {
  Skeleton skeleton;
  AsfInfo info;
  ReadTiny(&skeleton, &info);
  const std::string frames = "1\nroot 0 0 0 0.1 0.2 0.3\nthigh 0 0 0\nshin 0.5\nspine 0 0\n";
  Motion motion;
  ASSERT_TRUE(ParseAmc(":RADIANS\n" + frames, "r.amc", skeleton, info, 30.0, &motion).ok());
  EXPECT_TRUE(motion.frames[0].rotations[3].toRotationMatrix().isApprox(
      Rot(0, RadToDeg(0.5)), 1e-14));
  // Without a keyword the ASF's ':units angle' (deg here) applies.
  ASSERT_TRUE(ParseAmc(frames, "d.amc", skeleton, info, 30.0, &motion).ok());
  EXPECT_TRUE(motion.frames[0].rotations[3].toRotationMatrix().isApprox(Rot(0, 0.5), 1e-14));
}

// Acclaim forward kinematics written straight from the ASF/AMC definitions with
// matrices, independent of the Skeleton mapping: W_b = W_parent C_b M_b C_b^-1, a bone
// starts at its parent's tail (root children at the root) and ends at
// start + W_b d_b L_b. Angle values are in degrees.
struct AcclaimFrame {
  std::vector<double> root;                 // In ':root order'.
  std::vector<std::vector<double>> bones;   // Per bone, in dof order.
};

Eigen::Matrix3d AxisMatrix(const Eigen::Vector3d& xyz_deg, const std::string& order) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  for (char c : order) {
    const int axis = c - 'X';
    m = Rot(axis, xyz_deg[axis]) * m;
  }
  return m;
}

Eigen::Matrix3d DofMatrix(const std::vector<AsfDof>& dofs, const std::vector<double>& values) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  for (size_t k = 0; k < dofs.size(); ++k) {
    if (IsRotationDof(dofs[k].dof)) m = Rot(AcclaimDofAxis(dofs[k].dof), values[k]) * m;
  }
  return m;
}

// Compares our FK (joint positions, joint frames, end sites) with the direct Acclaim
// computation for one frame.
void ExpectMatchesAcclaim(const Skeleton& skeleton, const AsfInfo& info,
                          const AcclaimFrame& frame, const Pose& pose, double tolerance) {
  const int n = skeleton.num_joints();
  std::vector<Eigen::Matrix3d> world(n);
  std::vector<Eigen::Vector3d> start(n), tail(n);
  Eigen::Vector3d root = info.root_position;
  for (size_t k = 0; k < info.root_order.size(); ++k) {
    if (!IsRotationDof(info.root_order[k].dof)) {
      root[AcclaimDofAxis(info.root_order[k].dof)] += frame.root[k];
    }
  }
  const Eigen::Matrix3d c_root = AxisMatrix(info.root_orientation_deg, info.root_axis_order);
  world[0] = c_root * DofMatrix(info.root_order, frame.root) * c_root.transpose();
  start[0] = tail[0] = root;
  for (int j = 1; j < n; ++j) {
    const int b = info.bone_of_joint[j];
    const AsfBone& bone = info.bones[b];
    const Eigen::Matrix3d c = AxisMatrix(bone.axis_deg, bone.axis_order);
    const int p = skeleton.parent(j);
    world[j] = world[p] * c * DofMatrix(bone.dofs, frame.bones[b]) * c.transpose();
    start[j] = tail[p];
    tail[j] = start[j] + world[j] * bone.direction * bone.length;
  }
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose, &fk);
  for (int j = 0; j < n; ++j) {
    EXPECT_LT((fk.world_positions[j] - start[j]).norm(), tolerance) << skeleton.name(j);
    // The joint frame is W_b C_b.
    const Eigen::Matrix3d c = j == 0 ? c_root
                                     : AxisMatrix(info.bones[info.bone_of_joint[j]].axis_deg,
                                                  info.bones[info.bone_of_joint[j]].axis_order);
    EXPECT_TRUE(fk.world_rotations[j].toRotationMatrix().isApprox(world[j] * c, 1e-12))
        << skeleton.name(j);
  }
  const Vector3dVector sites = EndSitePositions(skeleton, fk);
  for (size_t s = 0; s < sites.size(); ++s) {
    EXPECT_LT((sites[s] - tail[skeleton.end_sites()[s].parent]).norm(), tolerance)
        << skeleton.end_sites()[s].name;
  }
}

// Random AMC text for the skeleton (values in degrees, printed exactly), and the values.
std::string RandomAmc(const AsfInfo& info, int frames, std::mt19937* rng,
                      std::vector<AcclaimFrame>* values) {
  std::uniform_real_distribution<double> angle(-180.0, 180.0), position(-50.0, 50.0);
  std::string text = ":FULLY-SPECIFIED\n:DEGREES\n";
  char buffer[64];
  values->assign(frames, {});
  for (int f = 0; f < frames; ++f) {
    AcclaimFrame& frame = (*values)[f];
    text += std::to_string(f + 1) + "\nroot";
    for (const AsfDof& dof : info.root_order) {
      frame.root.push_back(IsRotationDof(dof.dof) ? angle(*rng) : position(*rng));
      std::snprintf(buffer, sizeof buffer, " %.17g", frame.root.back());
      text += buffer;
    }
    text += "\n";
    frame.bones.resize(info.bones.size());
    for (size_t b = 0; b < info.bones.size(); ++b) {
      if (info.bones[b].dofs.empty()) continue;
      text += info.bones[b].name;
      for (size_t k = 0; k < info.bones[b].dofs.size(); ++k) {
        frame.bones[b].push_back(angle(*rng));
        std::snprintf(buffer, sizeof buffer, " %.17g", frame.bones[b].back());
        text += buffer;
      }
      text += "\n";
    }
  }
  return text;
}

TEST(AmcReader, MatchesDirectAcclaimKinematicsOnTinySkeleton) {
  Skeleton skeleton;
  AsfInfo info;
  ReadTiny(&skeleton, &info);
  std::mt19937 rng(11);
  std::vector<AcclaimFrame> values;
  const std::string text = RandomAmc(info, 20, &rng, &values);
  Motion motion;
  const Status status = ParseAmc(text, "random.amc", skeleton, info, 120.0, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(motion.num_frames(), 20);
  for (int f = 0; f < 20; ++f) {
    SCOPED_TRACE(f);
    // Lengths are ~10 units: 1e-12 is round-off.
    ExpectMatchesAcclaim(skeleton, info, values[f], motion.frames[f], 1e-12);
  }
}

TEST(AmcReader, MatchesDirectAcclaimKinematicsOnCmuSkeleton) {
  MOCAPSOLVE_DATA_FILE(asf_path, "amc/16.asf");
  Skeleton skeleton;
  AsfInfo info;
  ASSERT_TRUE(ReadAsf(asf_path, &skeleton, &info).ok());
  std::mt19937 rng(12);
  std::vector<AcclaimFrame> values;
  const std::string text = RandomAmc(info, 20, &rng, &values);
  Motion motion;
  const Status status = ParseAmc(text, "random.amc", skeleton, info, 120.0, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  for (int f = 0; f < 20; ++f) {
    SCOPED_TRACE(f);
    // Chains of ~10 bones over ~60 units: 1e-11 is round-off.
    ExpectMatchesAcclaim(skeleton, info, values[f], motion.frames[f], 1e-11);
  }
}

TEST(AmcReader, RotationSeriesAreSignContinuous) {
  Skeleton skeleton;
  AsfInfo info;
  ReadTiny(&skeleton, &info);
  // The root turns about y through 180 and on to 350 degrees, where a naive
  // conversion flips the quaternion's sign.
  std::string text;
  for (int f = 0; f < 36; ++f) {
    text += std::to_string(f + 1) + "\nroot 0 0 0 0 " + std::to_string(f * 10) +
            " 0\nthigh 0 0 0\nshin " + std::to_string(f * 10 - 180) + "\nspine 0 0\n";
  }
  Motion motion;
  ASSERT_TRUE(ParseAmc(text, "turn.amc", skeleton, info, 120.0, &motion).ok());
  for (int f = 1; f < motion.num_frames(); ++f) {
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      EXPECT_GE(motion.frames[f].rotations[j].dot(motion.frames[f - 1].rotations[j]), 0.0)
          << "frame " << f << " joint " << skeleton.name(j);
    }
  }
}

TEST(AmcReader, ErrorsNameFileAndLine) {
  Skeleton skeleton;
  AsfInfo info;
  ReadTiny(&skeleton, &info);
  const std::string frame1 = "1\nroot 1 2 3 4 5 6\nthigh 1 2 3\nshin 4\nspine 5 6\n";
  struct Case {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"", "t.amc:1: no frames"},
      {":FULLY-SPECIFIED\n:DEGREES\n", "t.amc:2: no frames"},
      {"root 1 2 3 4 5 6\n", "t.amc:1: expected a frame number before bone data"},
      {frame1 + "2\nroot 1 2 3 4 5 6\n", "t.amc:6: frame 2 has no line for 'thigh'"},
      {frame1 + ":DEGREES\n", "t.amc:6: keyword ':DEGREES' after the first frame"},
      {frame1 + "3\n", "t.amc:6: frame 3 follows frame 1"},
      {frame1 + "0\n", "t.amc:6: frame 0 follows frame 1"},
      {frame1 + "99999999999999999999999\n", "t.amc:6: unknown bone '99999999999999999999999'"},
      {frame1 + "2\nknee 1\n", "t.amc:7: unknown bone 'knee'"},
      {frame1 + "2\nroot 1 2 3 4 5\n", "t.amc:7: bone 'root' has 6 dofs, got 5 values"},
      {frame1 + "2\nshin 1 2\n", "t.amc:7: bone 'shin' has 1 dofs, got 2 values"},
      {frame1 + "2\nshin inf\n", "t.amc:7: bad number 'inf' for 'shin' rx"},
      {frame1 + "2\nshin 1e400\n", "t.amc:7: bad number '1e400'"},
      {frame1 + "2\nshin 0x10\n", "t.amc:7: bad number '0x10'"},
      {frame1 + "2\nhip 0\n", "t.amc:7: bone 'hip' has 0 dofs, got 1 values"},
      {frame1 + "2\nshin 1\nshin 2\n", "t.amc:8: bone 'shin' repeated in frame 2 (first at line 7)"},
  };
  for (const Case& c : cases) {
    Motion motion;
    const Status status = ParseAmc(c.text, "t.amc", skeleton, info, 120.0, &motion);
    ASSERT_FALSE(status.ok()) << c.expected;
    const std::string prefix = c.expected.substr(0, c.expected.find(": ") + 2);
    EXPECT_EQ(status.message().rfind(prefix, 0), 0u) << status.message() << "\nexpected " << c.expected;
    EXPECT_NE(status.message().find(c.expected.substr(prefix.size())), std::string::npos)
        << status.message() << "\nexpected " << c.expected;
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
  }
  // Caller errors are reported too, not crashed on.
  Motion motion;
  EXPECT_FALSE(ParseAmc(frame1, "t.amc", skeleton, info, 0.0, &motion).ok());
  EXPECT_FALSE(ParseAmc(frame1, "t.amc", skeleton, info, std::nan(""), &motion).ok());
  AsfInfo other = info;
  other.bones.pop_back();
  EXPECT_FALSE(ParseAmc(frame1, "t.amc", skeleton, other, 120.0, &motion).ok());
  other = info;
  other.bones[0].joint = 99;
  EXPECT_FALSE(ParseAmc(frame1, "t.amc", skeleton, other, 120.0, &motion).ok());
  EXPECT_FALSE(ReadAmc("/nonexistent/x.amc", skeleton, info, 120.0, &motion).ok());
}

// Each tests/data/bad/bad_*.amc starts with "# expect-error: line N: <part of the message>"
// and is read against tests/data/bad/tiny_ok.asf.
TEST(AmcReader, BadFilesGiveOneLineErrorsWithFileAndLine) {
  Skeleton skeleton;
  AsfInfo info;
  Status status = ReadAsf(testing::SourcePath("tests/data/bad/tiny_ok.asf"), &skeleton, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  const int checked = testing::CheckAnnotatedBadFiles(".amc", [&](const std::string& path) {
    Motion motion;
    return ReadAmc(path, skeleton, info, 120.0, &motion);
  });
  EXPECT_GE(checked, 4);
}

TEST(AmcReader, SurvivesRandomDamage) {
  Skeleton skeleton;
  AsfInfo info;
  ReadTiny(&skeleton, &info);
  std::mt19937 rng(20240522);
  const std::string base = kTinyAmc;
  std::string alphabet = "#:\n\r\t -.0123456789eEinfa root hip shin spine thigh";
  alphabet += '\0';
  alphabet += '\xff';
  int parsed = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const std::string text = testing::RandomlyDamaged(base, alphabet, &rng);
    Motion motion;
    const Status status = ParseAmc(text, "fuzz.amc", skeleton, info, 120.0, &motion);
    if (status.ok()) {
      ++parsed;
      EXPECT_TRUE(ValidateMotion(skeleton, motion).ok());
    } else {
      EXPECT_EQ(status.message().rfind("fuzz.amc:", 0), 0u) << status.message();
      EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
    }
  }
  EXPECT_GT(parsed, 0);
}

struct CmuTake {
  const char* asf;
  const char* amc;
  int frames;
  double root_first[6];  // The first frame's root line.
};

class CmuAmcTest : public ::testing::TestWithParam<CmuTake> {};

TEST_P(CmuAmcTest, Reads) {
  const CmuTake& take = GetParam();
  MOCAPSOLVE_DATA_FILE(asf_path, take.asf);
  MOCAPSOLVE_DATA_FILE(amc_path, take.amc);
  Skeleton skeleton;
  AsfInfo info;
  Status status = ReadAsf(asf_path, &skeleton, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  Motion motion;
  status = ReadAmc(amc_path, skeleton, info, 120.0, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(motion.num_frames(), take.frames);
  EXPECT_EQ(motion.frame_rate, 120.0);
  EXPECT_TRUE(ValidateMotion(skeleton, motion).ok());
  const Pose& first = motion.frames[0];
  EXPECT_LT((first.translations[0] -
             Eigen::Vector3d(take.root_first[0], take.root_first[1], take.root_first[2]))
                .norm(),
            1e-12);
  EXPECT_LT(AngularDistance(first.rotations[0],
                            Eigen::Quaterniond(Rot(2, take.root_first[5]) *
                                               Rot(1, take.root_first[4]) *
                                               Rot(0, take.root_first[3]))),
            1e-12);
  for (int f = 1; f < motion.num_frames(); ++f) {
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      ASSERT_GE(motion.frames[f].rotations[j].dot(motion.frames[f - 1].rotations[j]), 0.0);
    }
  }
  // The root stays within a few metres of the origin and above the floor-ish.
  FkData fk(skeleton);
  ForwardKinematics(skeleton, motion.frames[take.frames / 2], &fk);
  EXPECT_LT(fk.world_positions[0].norm() * skeleton.unit().metres_per_unit, 10.0);
}

INSTANTIATE_TEST_SUITE_P(
    CmuFiles, CmuAmcTest,
    ::testing::Values(
        CmuTake{"amc/01.asf", "amc/01_01.amc", 2751,
                {9.37216, 17.8693, -17.3198, -2.01677, -7.59696, -3.23164}},
        CmuTake{"amc/02.asf", "amc/02_01.amc", 343,
                {10.4194, 16.7048, -30.1003, -2.48972, -9.82194, -3.00914}},
        CmuTake{"amc/16.asf", "amc/16_15.amc", 471,
                {1.22935, 17.2598, -26.9208, 0.489518, -4.81374, -3.87663}}),
    [](const ::testing::TestParamInfo<CmuTake>& info) {
      return std::string(info.param.amc).substr(4, 5);
    });

}  // namespace
}  // namespace mocapsolve
