#include "io/bvh_writer.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "io/bvh_reader.h"
#include "kinematics/compact_motion.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

const std::vector<Channel> kPositions = {Channel::kXposition, Channel::kYposition,
                                         Channel::kZposition};
const std::vector<Channel> kZxy = {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};

std::vector<Channel> Concat(std::vector<Channel> a, const std::vector<Channel>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

JointSpec Joint(const std::string& name, int parent, const Eigen::Vector3d& offset,
                std::vector<Channel> channels) {
  JointSpec spec;
  spec.name = name;
  spec.parent = parent;
  spec.offset = offset;
  spec.channels = std::move(channels);
  return spec;
}

Skeleton MakeSkeleton(std::vector<JointSpec> joints, std::vector<EndSite> end_sites = {}) {
  Skeleton skeleton;
  const Status status =
      Skeleton::Create(std::move(joints), std::move(end_sites), LengthUnit(), &skeleton);
  EXPECT_TRUE(status.ok()) << status.message();
  return skeleton;
}

// Root with positions + ZXY, one child with ZXY and an end site.
Skeleton TwoJoints() {
  EndSite site;
  site.name = "Chest_End";
  site.parent = 1;
  site.offset = Eigen::Vector3d(0, 5, 0);
  return MakeSkeleton({Joint("Hips", -1, {1, 2, 3}, Concat(kPositions, kZxy)),
                       Joint("Chest", 0, {0, 10, 0}, kZxy)},
                      {site});
}

Eigen::Quaterniond RandomRotation(std::mt19937* random) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(*random), normal(*random), normal(*random), normal(*random));
  return q.normalized();
}

// A motion of `frames` random poses; translations of joints with position channels are
// random, the others keep their offsets.
Motion RandomMotion(const Skeleton& skeleton, int frames, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-50.0, 50.0);
  Motion motion;
  motion.frame_rate = 120.0;
  for (int f = 0; f < frames; ++f) {
    Pose pose = RestPose(skeleton);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      pose.rotations[j] = RandomRotation(&random);
      if (skeleton.has_translation_channels(j)) {
        pose.translations[j] = Eigen::Vector3d(uniform(random), uniform(random), uniform(random));
      }
    }
    motion.frames.push_back(pose);
  }
  return motion;
}

Status RoundTrip(const Skeleton& skeleton, const Motion& motion, const BvhWriteOptions& options,
                 Skeleton* read_skeleton, Motion* read_motion, std::string* text = nullptr) {
  const std::string written = FormatBvh(skeleton, motion, options);
  if (written.empty()) return Status::Error("FormatBvh returned nothing");
  if (text != nullptr) *text = written;
  return ParseBvh(written, "written.bvh", read_skeleton, read_motion);
}

// Worst rotation error of one Euler triple printed with `digits` significant digits, for
// angles below 1000 degrees: half a unit in the last place, 3 decimals, per angle.
double RotationTolerance(int digits) {
  return 3.0 * DegToRad(0.5 * std::pow(10.0, 3 - digits)) * 1.01;
}

TEST(BvhWriter, ExactTextOfASmallFile) {
  const Skeleton skeleton = TwoJoints();
  Motion motion;
  motion.frame_rate = 30.0;
  Pose pose = RestPose(skeleton);
  pose.translations[0] = Eigen::Vector3d(1.5, 2, -3);
  pose.rotations[0] = Eigen::AngleAxisd(DegToRad(90), Eigen::Vector3d::UnitZ());
  pose.rotations[1] = Eigen::AngleAxisd(DegToRad(30), Eigen::Vector3d::UnitX());
  motion.frames.push_back(pose);
  pose.translations[0] = Eigen::Vector3d(1.0 / 3.0, 1e-7, -12345678.0);
  motion.frames.push_back(pose);
  EXPECT_EQ(FormatBvh(skeleton, motion),
            "HIERARCHY\n"
            "ROOT Hips\n"
            "{\n"
            "\tOFFSET 1 2 3\n"
            "\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
            "\tJOINT Chest\n"
            "\t{\n"
            "\t\tOFFSET 0 10 0\n"
            "\t\tCHANNELS 3 Zrotation Xrotation Yrotation\n"
            "\t\tEnd Site\n"
            "\t\t{\n"
            "\t\t\tOFFSET 0 5 0\n"
            "\t\t}\n"
            "\t}\n"
            "}\n"
            "MOTION\n"
            "Frames: 2\n"
            "Frame Time: 0.03333333333333333\n"
            "1.5 2 -3 90 0 0 0 30 0\n"
            "0.333333 1e-07 -1.23457e+07 90 0 0 0 30 0\n");
}

TEST(BvhWriter, RoundTripKeepsLayoutAndValues) {
  const Skeleton skeleton = TwoJoints();
  const Motion motion = RandomMotion(skeleton, 20, 1);
  BvhWriteOptions options;
  options.precision = 12;
  Skeleton read_skeleton;
  Motion read_motion;
  const Status status = RoundTrip(skeleton, motion, options, &read_skeleton, &read_motion);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(read_skeleton.num_joints(), 2);
  EXPECT_EQ(read_skeleton.joint(0).channels, skeleton.joint(0).channels);
  EXPECT_EQ(read_skeleton.joint(1).channels, skeleton.joint(1).channels);
  EXPECT_EQ(read_skeleton.end_sites()[0].name, "Chest_End");
  EXPECT_EQ(read_skeleton.end_sites()[0].offset, Eigen::Vector3d(0, 5, 0));
  EXPECT_NEAR(read_motion.frame_rate, 120.0, 1e-12);
  ASSERT_EQ(read_motion.num_frames(), 20);
  for (int f = 0; f < 20; ++f) {
    for (int j = 0; j < 2; ++j) {
      EXPECT_LT(AngularDistance(read_motion.frames[f].rotations[j], motion.frames[f].rotations[j]),
                RotationTolerance(12));
      EXPECT_TRUE(read_motion.frames[f].translations[j].isApprox(motion.frames[f].translations[j],
                                                                 1e-11));
    }
  }
}

TEST(BvhWriter, EulerOrderOverrideForEveryOrder) {
  const Skeleton skeleton = TwoJoints();
  const Motion motion = RandomMotion(skeleton, 10, 2);
  for (int k = 0; k < 6; ++k) {
    const EulerOrder order = static_cast<EulerOrder>(k);
    SCOPED_TRACE(EulerOrderName(order));
    BvhWriteOptions options;
    options.euler_order = order;
    options.precision = 10;
    Skeleton read_skeleton;
    Motion read_motion;
    ASSERT_TRUE(RoundTrip(skeleton, motion, options, &read_skeleton, &read_motion).ok());
    for (int j = 0; j < 2; ++j) {
      const std::vector<Channel>& channels = read_skeleton.joint(j).channels;
      const std::vector<Channel> rotations(channels.end() - 3, channels.end());
      for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(static_cast<int>(rotations[i]), 3 + EulerAxis(order, i));
      }
    }
    EXPECT_EQ(read_skeleton.joint(0).channels.size(), 6u);
    for (int f = 0; f < motion.num_frames(); ++f) {
      for (int j = 0; j < 2; ++j) {
        EXPECT_LT(
            AngularDistance(read_motion.frames[f].rotations[j], motion.frames[f].rotations[j]),
            RotationTolerance(10));
      }
    }
  }
}

// Every order, at and near gimbal lock (middle angle +-90 degrees) and near 180.
TEST(BvhWriter, NastyRotationsRoundTrip) {
  const std::vector<Eigen::Vector3d> degrees = {
      {0, 90, 0},     {30, 90, -40},    {10, -90, 20},  {179.9, 89.999, -179.9},
      {180, 0, 180},  {-180, 45, 0},    {0, 0, 1e-12},  {90, 90, 90},
      {45, 89.9, 45}, {-120, -89.9, 5}, {179, 10, -179}};
  for (int k = 0; k < 6; ++k) {
    const EulerOrder order = static_cast<EulerOrder>(k);
    SCOPED_TRACE(EulerOrderName(order));
    const Skeleton skeleton = TwoJoints();
    Motion motion;
    motion.frame_rate = 60;
    for (const Eigen::Vector3d& d : degrees) {
      Pose pose = RestPose(skeleton);
      pose.rotations[0] = QuaternionFromEuler(d * (kPi / 180), order);
      pose.rotations[1] = QuaternionFromEuler(d * (kPi / 180), EulerOrder::kZXY);
      motion.frames.push_back(pose);
    }
    BvhWriteOptions options;
    options.euler_order = order;
    options.precision = 12;
    Skeleton read_skeleton;
    Motion read_motion;
    ASSERT_TRUE(RoundTrip(skeleton, motion, options, &read_skeleton, &read_motion).ok());
    for (int f = 0; f < motion.num_frames(); ++f) {
      for (int j = 0; j < 2; ++j) {
        EXPECT_LT(
            AngularDistance(read_motion.frames[f].rotations[j], motion.frames[f].rotations[j]),
            RotationTolerance(12))
            << "frame " << f << " joint " << j;
      }
    }
  }
}

TEST(BvhWriter, AnglesAreContinuousOverTime) {
  // A turn about Z from 150 to 250 degrees, then back: no jump at 180 in the file.
  const Skeleton skeleton = MakeSkeleton({Joint("R", -1, {0, 0, 0}, kZxy)});
  Motion motion;
  motion.frame_rate = 10;
  std::vector<double> expected;
  for (int step = 0; step <= 20; ++step) {
    const double z = step <= 10 ? 150 + 10 * step : 250 - 10 * (step - 10);
    expected.push_back(z);
    Pose pose = RestPose(skeleton);
    pose.rotations[0] = Eigen::AngleAxisd(DegToRad(z), Eigen::Vector3d::UnitZ());
    motion.frames.push_back(pose);
  }
  const std::string text = FormatBvh(skeleton, motion);
  std::istringstream in(text.substr(text.find("Frame Time:")));
  std::string line;
  std::getline(in, line);
  for (double z : expected) {
    ASSERT_TRUE(std::getline(in, line));
    double written_z, x, y;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf %lf", &written_z, &x, &y), 3) << line;
    EXPECT_NEAR(written_z, z, 1e-3) << line;
    EXPECT_NEAR(x, 0.0, 1e-9);
    EXPECT_NEAR(y, 0.0, 1e-9);
  }
}

// A long motion written in pieces (a take's windows, pipeline/take_windows.h) is the text
// FormatBvh makes of it whole: the angles continue across pieces (the turn past 180
// degrees of AnglesAreContinuousOverTime, cut in the middle of it); a later piece that moves
// a joint's translation the first piece's channels lack is an error naming the joint.
TEST(BvhWriter, PiecesMakeTheWholeText) {
  const Skeleton skeleton = TwoJoints();
  Motion motion = RandomMotion(skeleton, 12, 5);
  for (int f = 0; f < 12; ++f) {
    motion.frames[f].rotations[1] = Eigen::AngleAxisd(DegToRad(150.0 + 10.0 * f), Eigen::Vector3d::UnitZ());
  }
  Motion first, second;
  first.frame_rate = second.frame_rate = motion.frame_rate;
  first.frames.assign(motion.frames.begin(), motion.frames.begin() + 7);
  second.frames.assign(motion.frames.begin() + 4, motion.frames.end());  // Frames 4-11: 7-11 kept.
  BvhPieceWriter writer;
  ASSERT_TRUE(writer.Start(skeleton, first).ok());
  std::string text = writer.Header(12, motion.frame_rate);
  ASSERT_TRUE(writer.AppendFrames(first, 0, 7, &text).ok());
  ASSERT_TRUE(writer.AppendFrames(second, 3, 5, &text).ok());
  EXPECT_EQ(text, FormatBvh(skeleton, motion));
  second.frames[2].translations[1].x() += 1.0;  // Chest has no position channel.
  std::string more;
  const Status moved = writer.AppendFrames(second, 0, 1, &more);
  EXPECT_FALSE(moved.ok());
  EXPECT_NE(moved.message().find("Chest"), std::string::npos) << moved.message();
}

// A compact motion is written a piece of 1,024 frames at a time, its channels from the
// whole motion: the bytes of FormatBvh of it expanded, even when a joint's translation moves
// only in a later piece (Chest has no position channel and gets three).
TEST(BvhWriter, CompactMotionInPiecesIsTheWholeText) {
  const Skeleton skeleton = TwoJoints();
  Motion motion = RandomMotion(skeleton, 2500, 7);
  for (int f = 2100; f < 2200; ++f) motion.frames[f].translations[1].x() += 0.01 * (f - 2100);
  const CompactMotion compact(motion);
  const std::string path = testing::TempPath("compact.bvh");
  ASSERT_TRUE(WriteBvh(path, skeleton, compact).ok());
  const std::string text = testing::ReadTextFile(path);
  EXPECT_EQ(text, FormatBvh(skeleton, compact.ToMotion()));
  EXPECT_NE(text.find("CHANNELS 6 Xposition Yposition Zposition"), text.rfind("CHANNELS 6 Xposition"))
      << "Chest gets position channels";
  const std::string empty = testing::TempPath("empty.bvh");
  EXPECT_FALSE(WriteBvh(empty, skeleton, CompactMotion()).ok());
  struct stat st;
  EXPECT_NE(::stat(empty.c_str(), &st), 0) << "nothing written";
}

TEST(BvhWriter, ScaleMultipliesLengthsOnly) {
  const Skeleton skeleton = TwoJoints();
  const Motion motion = RandomMotion(skeleton, 5, 3);
  BvhWriteOptions options;
  options.scale = 2.54;
  options.precision = 12;
  Skeleton read_skeleton;
  Motion read_motion;
  ASSERT_TRUE(RoundTrip(skeleton, motion, options, &read_skeleton, &read_motion).ok());
  EXPECT_TRUE(read_skeleton.offset(0).isApprox(2.54 * skeleton.offset(0), 1e-12));
  EXPECT_TRUE(read_skeleton.offset(1).isApprox(2.54 * skeleton.offset(1), 1e-12));
  EXPECT_TRUE(read_skeleton.end_sites()[0].offset.isApprox(Eigen::Vector3d(0, 12.7, 0), 1e-12));
  for (int f = 0; f < 5; ++f) {
    EXPECT_TRUE(read_motion.frames[f].translations[0].isApprox(
        2.54 * motion.frames[f].translations[0], 1e-11));
    EXPECT_LT(AngularDistance(read_motion.frames[f].rotations[1], motion.frames[f].rotations[1]),
              RotationTolerance(12));
  }
}

TEST(BvhWriter, EmptyChannelsGetTheDefaultLayout) {
  const Skeleton skeleton = MakeSkeleton(
      {Joint("root", -1, {0, 1, 0}, {}), Joint("a", 0, {0, 1, 0}, {}), Joint("b", 1, {1, 0, 0}, {})});
  Motion motion = RandomMotion(skeleton, 3, 4);
  for (Pose& pose : motion.frames) pose.translations[0] = Eigen::Vector3d(4, 5, 6);
  Skeleton read_skeleton;
  Motion read_motion;
  BvhWriteOptions options;
  options.precision = 12;
  ASSERT_TRUE(RoundTrip(skeleton, motion, options, &read_skeleton, &read_motion).ok());
  EXPECT_EQ(read_skeleton.joint(0).channels, Concat(kPositions, kZxy));
  EXPECT_EQ(read_skeleton.joint(1).channels, kZxy);
  EXPECT_EQ(read_skeleton.joint(2).channels, kZxy);
  EXPECT_EQ(read_motion.frames[2].translations[0], Eigen::Vector3d(4, 5, 6));
}

TEST(BvhWriter, ChannelsAreCompletedWhenTheMotionNeedsThem) {
  // "a" has a single rotation channel and no positions; "b" positions only.
  const Skeleton skeleton = MakeSkeleton(
      {Joint("root", -1, {0, 0, 0}, Concat(kPositions, kZxy)),
       Joint("a", 0, {0, 1, 0}, {Channel::kYrotation}),
       Joint("b", 1, {1, 0, 0}, {Channel::kYposition})});
  Motion motion = RandomMotion(skeleton, 4, 5);
  // Translation of "a" animated without position channels; "b" animated on x too.
  for (int f = 0; f < motion.num_frames(); ++f) {
    motion.frames[f].translations[1] = Eigen::Vector3d(0, 1 + 0.1 * f, 0);
    motion.frames[f].translations[2] = Eigen::Vector3d(1 + 0.5 * f, -f, 0);
  }
  Skeleton read_skeleton;
  Motion read_motion;
  BvhWriteOptions options;
  options.precision = 12;
  ASSERT_TRUE(RoundTrip(skeleton, motion, options, &read_skeleton, &read_motion).ok());
  EXPECT_EQ(read_skeleton.joint(1).channels,
            (std::vector<Channel>{Channel::kXposition, Channel::kYposition, Channel::kZposition,
                                  Channel::kYrotation, Channel::kXrotation, Channel::kZrotation}));
  EXPECT_EQ(read_skeleton.joint(2).channels,
            (std::vector<Channel>{Channel::kXposition, Channel::kYposition, Channel::kZposition,
                                  Channel::kXrotation, Channel::kYrotation, Channel::kZrotation}));
  for (int f = 0; f < motion.num_frames(); ++f) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_TRUE(read_motion.frames[f].translations[j].isApprox(motion.frames[f].translations[j],
                                                                 1e-11));
      EXPECT_LT(AngularDistance(read_motion.frames[f].rotations[j], motion.frames[f].rotations[j]),
                RotationTolerance(12));
    }
  }
  // A layout the motion fits is kept as it is.
  Motion still;
  still.frame_rate = 30;
  still.frames.push_back(RestPose(skeleton));
  still.frames[0].rotations[1] = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY());
  still.frames[0].translations[2].y() = 7;
  ASSERT_TRUE(RoundTrip(skeleton, still, options, &read_skeleton, &read_motion).ok());
  EXPECT_EQ(read_skeleton.joint(1).channels,
            (std::vector<Channel>{Channel::kYrotation, Channel::kXrotation, Channel::kZrotation}));
  EXPECT_EQ(read_skeleton.joint(2).channels,
            (std::vector<Channel>{Channel::kYposition, Channel::kXrotation, Channel::kYrotation,
                                  Channel::kZrotation}));
  EXPECT_EQ(read_motion.frames[0].translations[2], Eigen::Vector3d(1, 7, 0));
}

// ASF-style rest rotations are folded into the written rotations; FK is unchanged.
TEST(BvhWriter, RestRotationsAreFoldedIn) {
  std::vector<JointSpec> joints = {Joint("root", -1, {0, 0, 0}, {}),
                                   Joint("femur", 0, {1, -2, 0.5}, {}),
                                   Joint("tibia", 1, {0, -4, 0}, {}),
                                   Joint("foot", 2, {0.3, -3, 1}, {})};
  std::mt19937 random(6);
  for (JointSpec& spec : joints) spec.rest_rotation = RandomRotation(&random);
  EndSite toe;
  toe.name = "toe";
  toe.parent = 3;
  toe.offset = Eigen::Vector3d(0, 0, 1.5);
  const Skeleton skeleton = MakeSkeleton(joints, {toe});
  ASSERT_TRUE(skeleton.has_rest_rotation(2));
  Motion motion = RandomMotion(skeleton, 15, 7);
  for (Pose& pose : motion.frames) pose.translations[0] = Eigen::Vector3d(3, 9, -1);

  Skeleton read_skeleton;
  Motion read_motion;
  BvhWriteOptions options;
  options.precision = 12;
  ASSERT_TRUE(RoundTrip(skeleton, motion, options, &read_skeleton, &read_motion).ok());
  EXPECT_FALSE(read_skeleton.has_rest_rotation(2));
  FkData original(skeleton), reread(read_skeleton);
  for (int f = 0; f < motion.num_frames(); ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &original);
    ForwardKinematics(read_skeleton, read_motion.frames[f], &reread);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      EXPECT_LT((original.world_positions[j] - reread.world_positions[j]).norm(), 1e-9);
      EXPECT_LT(AngularDistance(original.world_rotations[j], reread.world_rotations[j]), 1e-9);
      EXPECT_LT(AngularDistance(read_motion.frames[f].rotations[j],
                                skeleton.rest_rotation(j) * motion.frames[f].rotations[j]),
                RotationTolerance(12));
    }
    const Vector3dVector sites_before = EndSitePositions(skeleton, original);
    const Vector3dVector sites_after = EndSitePositions(read_skeleton, reread);
    EXPECT_LT((sites_before[0] - sites_after[0]).norm(), 1e-9);
  }
}

TEST(BvhWriter, JointsAreWrittenDepthFirst) {
  // Parents-first but not depth-first: 0 -> {1, 2}, 1 -> {3}.
  const Skeleton skeleton =
      MakeSkeleton({Joint("root", -1, {0, 0, 0}, Concat(kPositions, kZxy)),
                    Joint("left", 0, {1, 0, 0}, kZxy), Joint("right", 0, {-1, 0, 0}, kZxy),
                    Joint("left_knee", 1, {0, -1, 0}, kZxy)});
  const Motion motion = RandomMotion(skeleton, 3, 8);
  Skeleton read_skeleton;
  Motion read_motion;
  BvhWriteOptions options;
  options.precision = 12;
  ASSERT_TRUE(RoundTrip(skeleton, motion, options, &read_skeleton, &read_motion).ok());
  ASSERT_EQ(read_skeleton.num_joints(), 4);
  EXPECT_EQ(read_skeleton.name(2), "left_knee");
  EXPECT_EQ(read_skeleton.name(3), "right");
  for (int f = 0; f < 3; ++f) {
    for (int j = 0; j < 4; ++j) {
      const int r = read_skeleton.FindJoint(skeleton.name(j));
      EXPECT_LT(AngularDistance(read_motion.frames[f].rotations[r], motion.frames[f].rotations[j]),
                RotationTolerance(12));
    }
  }
}

TEST(BvhWriter, RejectsWhatItCannotWrite) {
  const Skeleton skeleton = TwoJoints();
  const Motion good = RandomMotion(skeleton, 2, 9);
  EXPECT_TRUE(CheckBvhWritable(skeleton, good, BvhWriteOptions()).ok());

  BvhWriteOptions bad_precision;
  bad_precision.precision = 0;
  EXPECT_FALSE(CheckBvhWritable(skeleton, good, bad_precision).ok());
  bad_precision.precision = 18;
  EXPECT_FALSE(CheckBvhWritable(skeleton, good, bad_precision).ok());
  BvhWriteOptions bad_scale;
  bad_scale.scale = 0.0;
  EXPECT_FALSE(CheckBvhWritable(skeleton, good, bad_scale).ok());
  bad_scale.scale = std::nan("");
  EXPECT_FALSE(CheckBvhWritable(skeleton, good, bad_scale).ok());
  bad_scale.scale = 1e308;  // Finite, but lengths times it are not.
  EXPECT_FALSE(CheckBvhWritable(skeleton, good, bad_scale).ok());

  Motion no_rate = good;
  no_rate.frame_rate = 0.0;
  Motion short_pose = good;
  short_pose.frames[1].rotations.pop_back();
  Motion non_finite = good;
  non_finite.frames[0].translations[0].x() = INFINITY;
  for (const Motion* bad : {&no_rate, &short_pose, &non_finite}) {
    const Status status = CheckBvhWritable(skeleton, *bad, BvhWriteOptions());
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(FormatBvh(skeleton, *bad), "");
    const std::string path = testing::TempPath("bad.bvh");
    const Status written = WriteBvh(path, skeleton, *bad);
    ASSERT_FALSE(written.ok());
    EXPECT_NE(written.message().find(path), std::string::npos) << written.message();
    struct stat st;
    EXPECT_NE(::stat(path.c_str(), &st), 0) << "a failed write left a file";
  }

  const Skeleton bad_name =
      MakeSkeleton({Joint("two\nlines", -1, {0, 0, 0}, Concat(kPositions, kZxy))});
  EXPECT_FALSE(CheckBvhWritable(bad_name, RandomMotion(bad_name, 1, 1), BvhWriteOptions()).ok());
}

TEST(BvhWriter, WriteBvhWritesAReadableFile) {
  const Skeleton skeleton = TwoJoints();
  const Motion motion = RandomMotion(skeleton, 4, 10);
  const std::string path = testing::TempPath("out.bvh");
  const Status status = WriteBvh(path, skeleton, motion, BvhWriteOptions());
  ASSERT_TRUE(status.ok()) << status.message();
  Skeleton read_skeleton;
  Motion read_motion;
  ASSERT_TRUE(ReadBvh(path, &read_skeleton, &read_motion).ok());
  EXPECT_EQ(read_motion.num_frames(), 4);

  const Status no_dir = WriteBvh("/nonexistent/dir/out.bvh", skeleton, motion, BvhWriteOptions());
  ASSERT_FALSE(no_dir.ok());
  EXPECT_NE(no_dir.message().find("/nonexistent/dir/out.bvh"), std::string::npos);
}

// Write with `precision` significant digits to a file, read back, compare.
// (Plain tests rather than TEST_P: TempPath makes one directory level per test name.)
void CheckRoundTrip(const char* relative, int precision) {
  MOCAPSOLVE_DATA_FILE(path, relative);
  Skeleton skeleton;
  Motion motion;
  const Status read = ReadBvh(path, &skeleton, &motion);
  ASSERT_TRUE(read.ok()) << read.message();

  const std::string out_path = testing::TempPath("roundtrip.bvh");
  BvhWriteOptions options;
  options.precision = precision;
  const Status written = WriteBvh(out_path, skeleton, motion, options);
  ASSERT_TRUE(written.ok()) << written.message();
  Skeleton again;
  Motion motion_again;
  const Status reread = ReadBvh(out_path, &again, &motion_again);
  ASSERT_TRUE(reread.ok()) << reread.message();

  ASSERT_EQ(again.num_joints(), skeleton.num_joints());
  ASSERT_EQ(motion_again.num_frames(), motion.num_frames());
  EXPECT_EQ(again.end_sites().size(), skeleton.end_sites().size());
  EXPECT_NEAR(motion_again.frame_rate, motion.frame_rate, 1e-9 * motion.frame_rate);
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    ASSERT_EQ(again.name(j), skeleton.name(j));
    EXPECT_EQ(again.parent(j), skeleton.parent(j));
    EXPECT_EQ(again.joint(j).channels, skeleton.joint(j).channels) << skeleton.name(j);
    EXPECT_TRUE(again.offset(j).isApprox(skeleton.offset(j), 1e-5) ||
                (again.offset(j) - skeleton.offset(j)).norm() < 1e-9);
  }

  // Rotations: `precision` significant digits of angles below 1000 degrees (the
  // tolerance's assumption, checked on the text below; the writer keeps them within
  // 360) give at most 3 x half a unit of the third decimal at precision 6.
  const double rotation_tolerance = RotationTolerance(precision);
  double worst_rotation = 0.0, worst_position = 0.0, worst_fk = 0.0;
  for (int f = 0; f < motion.num_frames(); ++f) {
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      const double angle =
          AngularDistance(motion_again.frames[f].rotations[j], motion.frames[f].rotations[j]);
      worst_rotation = std::max(worst_rotation, angle);
      ASSERT_LT(angle, rotation_tolerance) << "frame " << f << " joint " << skeleton.name(j);
      for (int i = 0; i < 3; ++i) {
        const double a = motion.frames[f].translations[j][i];
        const double b = motion_again.frames[f].translations[j][i];
        // 6 or more significant digits: relative error at most 5e-6.
        if (a != b) worst_position = std::max(worst_position, std::abs(a - b) / std::abs(a));
        ASSERT_LE(std::abs(a - b), 1e-4 * std::abs(a))
            << "frame " << f << " joint " << skeleton.name(j) << " axis " << i;
      }
    }
  }
  const std::vector<Vector3dVector> before = ClipJointPositions(skeleton, motion);
  const std::vector<Vector3dVector> after = ClipJointPositions(again, motion_again);
  for (size_t f = 0; f < before.size(); ++f) {
    for (size_t j = 0; j < before[f].size(); ++j) {
      const double distance = (before[f][j] - after[f][j]).norm();
      worst_fk = std::max(worst_fk, distance);
      ASSERT_LT(distance, 1e-3) << "frame " << f << " joint " << skeleton.name(j);
    }
  }
  std::string text;
  ASSERT_TRUE(ReadFileToString(out_path, &text).ok());
  const size_t data = text.find('\n', text.find("Frame Time:")) + 1;
  double largest_value = 0.0;
  for (const char* p = text.c_str() + data; *p != '\0';) {
    char* end;
    const double v = std::strtod(p, &end);
    if (end == p) break;
    largest_value = std::max(largest_value, std::abs(v));
    p = end;
  }
  // Angles (and positions) stayed below 1000, as the rotation tolerance assumes.
  EXPECT_LT(largest_value, 1000.0);
  std::printf("%s, precision %d: worst rotation %.3g rad, worst relative position %.3g, "
              "worst FK %.3g units, largest written value %g\n",
              relative, precision, worst_rotation, worst_position, worst_fk, largest_value);
  ::testing::Test::RecordProperty("worst_rotation_rad", std::to_string(worst_rotation));
  ::testing::Test::RecordProperty("worst_fk_units", std::to_string(worst_fk));
}

TEST(BvhRoundTrip, Cmu01_01) { CheckRoundTrip("bvh/01_01.bvh", 6); }
TEST(BvhRoundTrip, Cmu16_15) { CheckRoundTrip("bvh/16_15.bvh", 6); }
TEST(BvhRoundTrip, Cmu131_01) { CheckRoundTrip("bvh/131_01.bvh", 6); }
TEST(BvhRoundTrip, Cmu131_02) { CheckRoundTrip("bvh/131_02.bvh", 6); }
// At 8 digits the rotation bound is 2.6e-7 rad, well inside 1e-5.
TEST(BvhRoundTrip, Cmu01_01Precision8) { CheckRoundTrip("bvh/01_01.bvh", 8); }

}  // namespace
}  // namespace mocapsolve
