#include "io/bvh_reader.h"

#include <dirent.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// Rotations built independently of QuaternionFromEuler: the product of the listed
// axis rotations, left to right (BVH's intrinsic convention).
Eigen::Quaterniond Product(const std::string& axes, const std::vector<double>& degrees) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (size_t i = 0; i < axes.size(); ++i) {
    q = q * Eigen::AngleAxisd(DegToRad(degrees[i]), Eigen::Vector3d::Unit(axes[i] - 'X'));
  }
  return q;
}

// Rotations from the reader are compared as rotations; 1e-12 rad is double rounding.
constexpr double kRotationTolerance = 1e-12;

const char kTwoJoints[] =
    "HIERARCHY\n"
    "ROOT Hips\n"
    "{\n"
    "  OFFSET 1 2 3\n"
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    "  JOINT Chest\n"
    "  {\n"
    "    OFFSET 0 10 0\n"
    "    CHANNELS 3 Zrotation Xrotation Yrotation\n"
    "    End Site\n"
    "    {\n"
    "      OFFSET 0 5 0\n"
    "    }\n"
    "  }\n"
    "}\n"
    "MOTION\n"
    "Frames: 2\n"
    "Frame Time: 0.04\n"
    "1 2 3 10 20 30 40 50 60\n"
    "4 5 6 0 0 0 -15 0 0\n";

// True if `message` is "...NAME:LINE: <text>" (no std::regex: GCC 12's <regex> warns under
// the sanitizer build).
bool NamesFileAndLine(const std::string& message, const std::string& name) {
  const size_t at = message.find(name + ":");
  if (at == std::string::npos) return false;
  size_t p = at + name.size() + 1;
  const size_t digits_begin = p;
  while (p < message.size() && message[p] >= '0' && message[p] <= '9') ++p;
  return p > digits_begin && message.compare(p, 2, ": ") == 0 && message.size() > p + 2;
}

Status Parse(const std::string& text, Skeleton* skeleton, Motion* motion) {
  return ParseBvh(text, "test.bvh", skeleton, motion);
}

// A one-joint file with the given CHANNELS line and one frame of values.
std::string OneJoint(const std::string& channels, const std::string& values) {
  return "HIERARCHY\nROOT R\n{\n OFFSET 7 8 9\n CHANNELS " + channels +
         "\n}\nMOTION\nFrames: 1\nFrame Time: 0.01\n" + values + "\n";
}

TEST(BvhReader, ReadsHierarchyAndMotion) {
  Skeleton skeleton;
  Motion motion;
  const Status status = Parse(kTwoJoints, &skeleton, &motion);
  ASSERT_TRUE(status.ok()) << status.message();

  ASSERT_EQ(skeleton.num_joints(), 2);
  EXPECT_EQ(skeleton.name(0), "Hips");
  EXPECT_EQ(skeleton.name(1), "Chest");
  EXPECT_EQ(skeleton.parent(1), 0);
  EXPECT_EQ(skeleton.offset(0), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(skeleton.offset(1), Eigen::Vector3d(0, 10, 0));
  EXPECT_EQ(skeleton.joint(0).channels,
            (std::vector<Channel>{Channel::kXposition, Channel::kYposition, Channel::kZposition,
                                  Channel::kZrotation, Channel::kXrotation, Channel::kYrotation}));
  EXPECT_EQ(skeleton.joint(1).channels,
            (std::vector<Channel>{Channel::kZrotation, Channel::kXrotation, Channel::kYrotation}));
  EXPECT_TRUE(skeleton.has_translation_channels(0));
  EXPECT_FALSE(skeleton.has_translation_channels(1));
  EXPECT_FALSE(skeleton.has_rest_rotation(0));
  EXPECT_EQ(skeleton.unit().name, "unknown");
  EXPECT_FALSE(skeleton.unit().known());

  ASSERT_EQ(skeleton.end_sites().size(), 1u);
  EXPECT_EQ(skeleton.end_sites()[0].name, "Chest_End");
  EXPECT_EQ(skeleton.end_sites()[0].parent, 1);
  EXPECT_EQ(skeleton.end_sites()[0].offset, Eigen::Vector3d(0, 5, 0));

  EXPECT_DOUBLE_EQ(motion.frame_rate, 25.0);
  ASSERT_EQ(motion.num_frames(), 2);
  EXPECT_EQ(motion.frames[0].translations[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(motion.frames[1].translations[0], Eigen::Vector3d(4, 5, 6));
  // No position channels: the offset.
  EXPECT_EQ(motion.frames[1].translations[1], Eigen::Vector3d(0, 10, 0));
  EXPECT_LT(AngularDistance(motion.frames[0].rotations[0], Product("ZXY", {10, 20, 30})),
            kRotationTolerance);
  EXPECT_LT(AngularDistance(motion.frames[0].rotations[1], Product("ZXY", {40, 50, 60})),
            kRotationTolerance);
  EXPECT_LT(AngularDistance(motion.frames[1].rotations[1], Product("Z", {-15})),
            kRotationTolerance);
  EXPECT_TRUE(ValidateMotion(skeleton, motion).ok());
}

TEST(BvhReader, EveryRotationOrderIsAnIntrinsicProduct) {
  std::string axes = "XYZ";
  int orders = 0;
  do {
    SCOPED_TRACE(axes);
    const std::string channels = std::string("3 ") + axes[0] + "rotation " + axes[1] +
                                 "rotation " + axes[2] + "rotation";
    Skeleton skeleton;
    Motion motion;
    const Status status = Parse(OneJoint(channels, "30 -50 70"), &skeleton, &motion);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_LT(AngularDistance(motion.frames[0].rotations[0], Product(axes, {30, -50, 70})),
              kRotationTolerance);
    // The file's layout is kept.
    ASSERT_EQ(skeleton.joint(0).channels.size(), 3u);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(static_cast<int>(skeleton.joint(0).channels[i]), 3 + (axes[i] - 'X'));
    }
    ++orders;
  } while (std::next_permutation(axes.begin(), axes.end()));
  EXPECT_EQ(orders, 6);
}

TEST(BvhReader, PartialRotationChannels) {
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(Parse(OneJoint("2 Yrotation Xrotation", "25 -40"), &skeleton, &motion).ok());
  EXPECT_LT(AngularDistance(motion.frames[0].rotations[0], Product("YX", {25, -40})),
            kRotationTolerance);
  ASSERT_TRUE(Parse(OneJoint("1 Zrotation", "33"), &skeleton, &motion).ok());
  EXPECT_LT(AngularDistance(motion.frames[0].rotations[0], Product("Z", {33})),
            kRotationTolerance);
}

TEST(BvhReader, JointWithoutRotationChannelsHasIdentity) {
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(
      Parse(OneJoint("3 Xposition Yposition Zposition", "1 2 3"), &skeleton, &motion).ok());
  EXPECT_TRUE(motion.frames[0].rotations[0].isApprox(Eigen::Quaterniond::Identity(), 0.0));
  EXPECT_EQ(motion.frames[0].translations[0], Eigen::Vector3d(1, 2, 3));
}

TEST(BvhReader, PositionChannelsReplaceTheOffsetOnTheirAxesOnly) {
  Skeleton skeleton;
  Motion motion;
  // Positions after rotations, one axis only: y from the channel, x and z from OFFSET.
  ASSERT_TRUE(Parse(OneJoint("2 Zrotation Yposition", "90 -4.5"), &skeleton, &motion).ok());
  EXPECT_EQ(motion.frames[0].translations[0], Eigen::Vector3d(7, -4.5, 9));
  EXPECT_TRUE(skeleton.has_translation_channels(0));
  EXPECT_LT(AngularDistance(motion.frames[0].rotations[0], Product("Z", {90})),
            kRotationTolerance);
}

TEST(BvhReader, NonRootTranslationChannels) {
  const std::string text =
      "HIERARCHY\nROOT A\n{\n OFFSET 0 0 0\n CHANNELS 3 Zrotation Yrotation Xrotation\n"
      " JOINT B\n {\n  OFFSET 0 10 0\n"
      "  CHANNELS 6 Xposition Yposition Zposition Yrotation Xrotation Zrotation\n"
      "  End Site\n  {\n   OFFSET 0 1 0\n  }\n }\n}\n"
      "MOTION\nFrames: 1\nFrame Time: 0.5\n90 0 0 0.5 11 -0.25 0 0 0\n";
  Skeleton skeleton;
  Motion motion;
  const Status status = Parse(text, &skeleton, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(motion.frames[0].translations[1], Eigen::Vector3d(0.5, 11, -0.25));
  EXPECT_TRUE(skeleton.has_translation_channels(1));
  // FK: B sits at Rz(90) * (0.5, 11, -0.25) = (-11, 0.5, -0.25).
  FkData fk(skeleton);
  ForwardKinematics(skeleton, motion.frames[0], &fk);
  EXPECT_TRUE(fk.world_positions[1].isApprox(Eigen::Vector3d(-11, 0.5, -0.25), 1e-12));
  EXPECT_DOUBLE_EQ(motion.frame_rate, 2.0);
}

TEST(BvhReader, CrlfTabsScientificNotationAndByteOrderMark) {
  std::string text =
      "\xEF\xBB\xBFHIERARCHY\r\nROOT\tHips\r\n{\r\n\tOFFSET\t1e1 -2.5E-1 +3\r\n"
      "\tCHANNELS 6 XPOSITION yposition Zposition Zrotation Xrotation Yrotation \r\n"
      "\tEnd Site\r\n\t{\r\n\t\tOFFSET .5 0 -0\r\n\t}\r\n}\r\n"
      "MOTION\r\nFrames:\t2\r\nFrame Time:\t8.3333e-3\r\n"
      "1.5e2\t-2E-2 +.25 0 0 0 \r\n"
      "\r\n"  // A blank line between frames is skipped.
      "  -1e+1 0 0 9e1 0 0\r\n"
      "\r\n";
  Skeleton skeleton;
  Motion motion;
  const Status status = Parse(text, &skeleton, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(skeleton.name(0), "Hips");
  EXPECT_EQ(skeleton.offset(0), Eigen::Vector3d(10, -0.25, 3));
  EXPECT_EQ(skeleton.end_sites()[0].offset, Eigen::Vector3d(0.5, 0, 0));
  EXPECT_NEAR(motion.frame_rate, 1.0 / 8.3333e-3, 1e-9);
  ASSERT_EQ(motion.num_frames(), 2);
  EXPECT_EQ(motion.frames[0].translations[0], Eigen::Vector3d(150, -0.02, 0.25));
  EXPECT_EQ(motion.frames[1].translations[0], Eigen::Vector3d(-10, 0, 0));
  EXPECT_LT(AngularDistance(motion.frames[1].rotations[0], Product("Z", {90})),
            kRotationTolerance);
}

TEST(BvhReader, JointNamesAreTheRestOfTheLine) {
  const std::string text =
      "HIERARCHY\nROOT mixamorig:Hips {\n OFFSET 0 0 0\n CHANNELS 1 Zrotation\n"
      " JOINT Left Up Leg\n {\n  OFFSET 1 0 0\n  CHANNELS 1 Xrotation\n"
      "  End Site\n  {\n   OFFSET 0 -1 0\n  }\n  End Site\n  {\n   OFFSET 0 -2 0\n  }\n }\n}\n"
      "MOTION\nFrames: 0\nFrame Time: 0.1\n";
  Skeleton skeleton;
  Motion motion;
  const Status status = Parse(text, &skeleton, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(skeleton.name(0), "mixamorig:Hips");
  EXPECT_EQ(skeleton.name(1), "Left Up Leg");
  ASSERT_EQ(skeleton.end_sites().size(), 2u);
  EXPECT_EQ(skeleton.end_sites()[0].name, "Left Up Leg_End");
  EXPECT_EQ(skeleton.end_sites()[1].name, "Left Up Leg_End2");
  EXPECT_EQ(motion.num_frames(), 0);
  EXPECT_DOUBLE_EQ(motion.frame_rate, 10.0);
}

TEST(BvhReader, QuaternionSeriesIsSignContinuous) {
  // Rz(170) and Rz(190) are 20 degrees apart, but their quaternions from Euler angles
  // have opposite w signs.
  std::string text = "HIERARCHY\nROOT R\n{\n OFFSET 0 0 0\n CHANNELS 1 Zrotation\n}\n"
                     "MOTION\nFrames: 5\nFrame Time: 0.01\n150\n170\n190\n210\n-150\n";
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(Parse(text, &skeleton, &motion).ok());
  for (int f = 1; f < motion.num_frames(); ++f) {
    EXPECT_GT(motion.frames[f].rotations[0].dot(motion.frames[f - 1].rotations[0]), 0.0)
        << "frame " << f;
  }
  EXPECT_LT(AngularDistance(motion.frames[2].rotations[0], Product("Z", {190})),
            kRotationTolerance);
}

struct BadInput {
  const char* what;
  std::string text;
  int line;                   // Expected in the message as "test.bvh:LINE:".
  const char* message_part;   // Expected somewhere in the message.
};

std::string WithMotion(const std::string& motion) {
  return "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n"
         " CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
         " JOINT Chest\n {\n  OFFSET 0 10 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n"
         "  End Site\n  {\n   OFFSET 0 5 0\n  }\n }\n}\n" +  // Lines 1-15.
         motion;
}

std::string WithChannels(const std::string& chest_channels) {
  return "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition Yposition Zposition\n"
         " JOINT Chest\n {\n  OFFSET 0 10 0\n  CHANNELS " +  // Chest's CHANNELS on line 9.
         chest_channels + "\n }\n}\nMOTION\nFrames: 0\nFrame Time: 0.1\n";
}

std::vector<BadInput> BadInputs() {
  const std::string header = "MOTION\nFrames: 2\nFrame Time: 0.01\n";  // Lines 16-18.
  return {
      {"empty", "", 1, "expected 'HIERARCHY', got end of file"},
      {"not BVH", "{\"json\": true}", 1, "expected 'HIERARCHY', got '{\"json\":'"},
      {"binary", std::string("\x89PNG\r\n\x1a\n\0\0\0", 11), 1, "got '\\x89PNG'"},
      {"no ROOT", "HIERARCHY\nJOINT Hips\n", 2, "expected 'ROOT', got 'JOINT'"},
      {"no name", "HIERARCHY\nROOT\n{\n", 2, "expected a joint name after ROOT"},
      {"no brace", "HIERARCHY\nROOT Hips\nOFFSET 0 0 0\n", 3, "expected '{', got 'OFFSET'"},
      {"non-numeric offset", "HIERARCHY\nROOT Hips\n{\n OFFSET 0 zero 0\n", 4,
       "expected a number within +-1e9 (OFFSET y), got 'zero'"},
      {"nan offset", "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 NaN\n", 4, "got 'NaN'"},
      {"short offset", "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0\n}\n", 5, "got '}'"},
      {"unknown channel", WithChannels("3 Zrotation Xrotation Wrotation"), 9,
       "expected a channel name (Xposition ... Zrotation), got 'Wrotation'"},
      {"channel count too large", WithChannels("7 Zrotation"), 9,
       "expected a channel count from 0 to 6, got '7'"},
      {"channel count not a number", WithChannels("three Zrotation"), 9, "got 'three'"},
      {"fewer channels than counted", WithChannels("3 Zrotation Xrotation"), 10,
       "expected a channel name (Xposition ... Zrotation), got '}'"},
      {"two rotation channels of one axis", WithChannels("3 Zrotation Xrotation Zrotation"), 9,
       "expected each channel at most once per joint, got 'Zrotation'"},
      {"a 4th rotation channel", WithChannels("4 Zrotation Xrotation Yrotation Xrotation"), 9,
       "expected each channel at most once per joint, got 'Xrotation'"},
      {"repeated position channel", WithChannels("2 Yposition Yposition"), 9,
       "at most once per joint"},
      {"two CHANNELS", WithChannels("1 Zrotation\n  CHANNELS 1 Xrotation"), 10,
       "expected one CHANNELS per joint"},
      {"duplicate joint name",
       "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n JOINT Leg\n {\n  OFFSET 0 0 0\n }\n"
       " JOINT Leg\n {\n",
       9, "expected a unique joint name, got 'Leg' (already used on line 5)"},
      {"child before OFFSET", "HIERARCHY\nROOT Hips\n{\n JOINT Leg\n", 4,
       "expected OFFSET before the first child"},
      {"block without OFFSET", "HIERARCHY\nROOT Hips\n{\n CHANNELS 0\n}\n", 5,
       "expected OFFSET before '}'"},
      {"End Sight", "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n End Sight\n", 5,
       "expected 'Site', got 'Sight'"},
      {"channels in End Site",
       "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n End Site\n {\n  OFFSET 0 1 0\n  CHANNELS 0\n",
       8, "expected OFFSET or '}' in End Site, got 'CHANNELS'"},
      {"unknown keyword", "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n ROTATION 1 2 3\n", 5,
       "expected OFFSET, CHANNELS, JOINT, End Site or '}', got 'ROTATION'"},
      {"missing closing brace (truncated hierarchy)",
       "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n JOINT Leg\n {\n  OFFSET 0 1 0\n }\n", 8,
       "expected '}' closing the joint 'Hips' opened on line 2, got end of file"},
      {"missing inner closing brace (MOTION inside a joint)",
       "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n JOINT Leg\n {\n  OFFSET 0 1 0\n}\nMOTION\n",
       9, "expected '}' closing the joint 'Hips' opened on line 2, got 'MOTION'"},
      {"extra closing brace", "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n}\n}\nMOTION\n", 6,
       "expected MOTION, got '}'"},
      {"second ROOT", "HIERARCHY\nROOT A\n{\n OFFSET 0 0 0\n}\nROOT B\n", 6,
       "expected MOTION (only one ROOT is supported), got 'ROOT'"},
      {"no MOTION", "HIERARCHY\nROOT A\n{\n OFFSET 0 0 0\n}\n", 5, "expected MOTION, got end of file"},
      {"missing Frames:", WithMotion("MOTION\nFrame Time: 0.01\n"), 17,
       "expected 'Frames:', got 'Frame'"},
      {"negative frame count", WithMotion("MOTION\nFrames: -3\n"), 17,
       "expected a frame count, got '-3'"},
      {"fractional frame count", WithMotion("MOTION\nFrames: 2.5\n"), 17, "got '2.5'"},
      {"frame count overflow", WithMotion("MOTION\nFrames: 99999999999999999999\n"), 17,
       "expected a frame count"},
      {"missing Frame Time:", WithMotion("MOTION\nFrames: 1\n0 0 0 0 0 0 0 0 0\n"), 18,
       "expected 'Frame', got '0'"},
      {"zero frame time", WithMotion("MOTION\nFrames: 1\nFrame Time: 0\n"), 18,
       "expected a frame time of 1e-6 to 1000 seconds, got '0'"},
      {"negative frame time", WithMotion("MOTION\nFrames: 1\nFrame Time: -0.01\n"), 18,
       "got '-0.01'"},
      {"inf frame time", WithMotion("MOTION\nFrames: 1\nFrame Time: inf\n"), 18, "got 'inf'"},
      {"data on the Frame Time line",
       WithMotion("MOTION\nFrames: 1\nFrame Time: 0.01 0 0 0 0 0 0 0 0 0\n"), 18,
       "expected end of line after the frame time, got '0 0 0"},
      {"too few values", WithMotion(header + "0 0 0 0 0 0 0 0 0\n0 0 0 0 0 0 0 0\n"), 20,
       "expected 9 values in frame 2, got 8"},
      {"too many values", WithMotion(header + "0 0 0 0 0 0 0 0 0 0 0\n"), 19,
       "expected 9 values in frame 1, got 11"},
      {"non-numeric value", WithMotion(header + "0 0 0 0 0 0 0 x 0\n"), 19,
       "expected a number within +-1e9 (frame 1, joint 'Chest' Xrotation), got 'x'"},
      {"number with trailing junk", WithMotion(header + "0 0 0 0 0 0 0 1.5abc 0\n"), 19,
       "got '1.5abc'"},
      {"nan value", WithMotion(header + "0 0 0 0 0 0 0 0 0\n0 nan 0 0 0 0 0 0 0\n"), 20,
       "expected a number within +-1e9 (frame 2, joint 'Hips' Yposition), got 'nan'"},
      {"inf value", WithMotion(header + "0 0 0 0 0 0 0 0 0\n0 0 0 0 -inf 0 0 0 0\n"), 20,
       "got '-inf'"},
      {"out-of-range value", WithMotion(header + "1e400 0 0 0 0 0 0 0 0\n"), 19,
       "got '1e400'"},
      {"truncated motion", WithMotion(header + "0 0 0 0 0 0 0 0 0\n"), 19,
       "expected frame 2 of 2 (9 values), got end of file"},
      {"truncated motion without final newline", WithMotion(header + "0 0 0 0 0 0 0 0 0"), 19,
       "expected frame 2 of 2"},
      {"huge frame count with no data",
       WithMotion("MOTION\nFrames: 2000000000\nFrame Time: 0.01\n0 0 0 0 0 0 0 0 0\n"), 19,
       "expected frame 2 of 2000000000"},
      {"extra frames", WithMotion(header + "0 0 0 0 0 0 0 0 0\n0 0 0 0 0 0 0 0 0\n1 2 3\n"), 21,
       "expected end of file after 2 frames, got '1'"},
      {"frames but no channels",
       "HIERARCHY\nROOT A\n{\n OFFSET 0 0 0\n}\nMOTION\nFrames: 3\nFrame Time: 1\n", 7,
       "expected CHANNELS on at least one joint"},
  };
}

TEST(BvhReader, MalformedInputGivesOneLineWithTheLineNumber) {
  for (const BadInput& bad : BadInputs()) {
    SCOPED_TRACE(bad.what);
    Skeleton skeleton;
    Motion motion;
    const Status status = Parse(bad.text, &skeleton, &motion);
    ASSERT_FALSE(status.ok());
    const std::string& message = status.message();
    EXPECT_EQ(message.rfind("test.bvh:" + std::to_string(bad.line) + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(bad.message_part), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(BvhReader, ErrorLeavesOutputsUntouched) {
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(Parse(kTwoJoints, &skeleton, &motion).ok());
  ASSERT_FALSE(Parse(WithMotion("MOTION\nFrames: 1\nFrame Time: 0\n"), &skeleton, &motion).ok());
  EXPECT_EQ(skeleton.num_joints(), 2);
  EXPECT_EQ(motion.num_frames(), 2);
}

// Every prefix and a seeded set of byte mutations of a valid file: never a crash, a hang
// or an exception; every failure names the file and a line.
TEST(BvhReader, SurvivesTruncationAndCorruption) {
  const std::string valid = kTwoJoints;
  int failures = 0;
  for (size_t n = 0; n < valid.size(); ++n) {
    Skeleton skeleton;
    Motion motion;
    const Status status = Parse(valid.substr(0, n), &skeleton, &motion);
    if (!status.ok()) {
      ++failures;
      EXPECT_TRUE(NamesFileAndLine(status.message(), "test.bvh")) << status.message();
    }
  }
  EXPECT_GT(failures, static_cast<int>(valid.size()) * 9 / 10);

  std::mt19937 random(20240611);
  const char kBytes[] = "{} \n\r\t0123456789.-+eE:xXnN\x00\xff";
  for (int trial = 0; trial < 3000; ++trial) {
    std::string text = valid;
    const int edits = 1 + trial % 4;
    for (int e = 0; e < edits; ++e) {
      const size_t at = random() % text.size();
      const char byte = kBytes[random() % (sizeof kBytes - 1)];
      switch (random() % 3) {
        case 0: text[at] = byte; break;
        case 1: text.insert(text.begin() + at, byte); break;
        default: text.erase(at, 1 + random() % 8); break;
      }
      if (text.empty()) text = "x";
    }
    Skeleton skeleton;
    Motion motion;
    const Status status = Parse(text, &skeleton, &motion);
    if (status.ok()) {
      EXPECT_TRUE(ValidateMotion(skeleton, motion).ok());
    } else {
      EXPECT_TRUE(NamesFileAndLine(status.message(), "test.bvh")) << status.message();
    }
  }
}

// 20000 joints without channels and 50000 one-value frames: 1e9 joint-frames (56 GB of
// poses) from a 0.6 MB file must be refused, not allocated.
TEST(BvhReader, RefusesMotionsFarLargerThanTheirFile) {
  std::string text = "HIERARCHY\nROOT R\n{\nOFFSET 0 0 0\nCHANNELS 1 Zrotation\n";
  for (int j = 0; j < 20000; ++j) text += "JOINT j" + std::to_string(j) + "\n{\nOFFSET 0 0 0\n}\n";
  text += "}\nMOTION\nFrames: 50000\nFrame Time: 0.01\n";
  for (int f = 0; f < 50000; ++f) text += "0\n";
  Skeleton skeleton;
  Motion motion;
  const Status status = Parse(text, &skeleton, &motion);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("too many joints without channels"), std::string::npos)
      << status.message();
  EXPECT_TRUE(NamesFileAndLine(status.message(), "test.bvh")) << status.message();
}

TEST(BvhReader, MissingFileNamesThePath) {
  Skeleton skeleton;
  Motion motion;
  const Status status = ReadBvh("/nonexistent/walk.bvh", &skeleton, &motion);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("/nonexistent/walk.bvh"), std::string::npos);
}

// tests/data/bad/*.bvh: every file fails with its name and a line number.
TEST(BvhReader, BadFileCorpus) {
  const std::string dir = testing::SourcePath("tests/data/bad");
  std::vector<std::string> names;
  if (DIR* d = opendir(dir.c_str())) {
    while (const dirent* entry = readdir(d)) {
      const std::string name = entry->d_name;
      if (name.size() > 4 && name.compare(0, 4, "bad_") == 0 &&
          name.compare(name.size() - 4, 4, ".bvh") == 0) {
        names.push_back(name);
      }
    }
    closedir(d);
  }
  std::sort(names.begin(), names.end());
  ASSERT_GE(names.size(), 8u) << "bad BVH corpus missing under " << dir;
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const std::string path = dir + "/" + name;
    Skeleton skeleton;
    Motion motion;
    const Status status = ReadBvh(path, &skeleton, &motion);
    ASSERT_FALSE(status.ok());
    EXPECT_TRUE(NamesFileAndLine(status.message(), path)) << status.message();
    EXPECT_NE(status.message().find(": expected "), std::string::npos) << status.message();
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
  }
}

struct RealFile {
  const char* path;
  int joints;
  int frames;
  int channels;
  int end_sites;
  double frame_time;
};

class BvhRealData : public ::testing::TestWithParam<RealFile> {};

// Counts from /work/shared/data/README.md ("BVH").
INSTANTIATE_TEST_SUITE_P(Files, BvhRealData,
                         ::testing::Values(RealFile{"bvh/01_01.bvh", 31, 2752, 96, 7, .0083333},
                                           RealFile{"bvh/16_15.bvh", 29, 471, 90, 7, 0.00833333},
                                           RealFile{"bvh/131_01.bvh", 31, 994, 96, 7, .0083333},
                                           RealFile{"bvh/131_02.bvh", 31, 1247, 96, 7,
                                                    .0083333}),
                         [](const ::testing::TestParamInfo<RealFile>& info) {
                           std::string name = info.param.path + 4;
                           return "cmu_" + name.substr(0, name.size() - 4);
                         });

TEST_P(BvhRealData, LoadsWithTheDocumentedCounts) {
  MOCAPSOLVE_DATA_FILE(path, GetParam().path);
  Skeleton skeleton;
  Motion motion;
  const Status status = ReadBvh(path, &skeleton, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(skeleton.num_joints(), GetParam().joints);
  EXPECT_EQ(motion.num_frames(), GetParam().frames);
  EXPECT_EQ(static_cast<int>(skeleton.end_sites().size()), GetParam().end_sites);
  int channels = 0;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    channels += static_cast<int>(skeleton.joint(j).channels.size());
  }
  EXPECT_EQ(channels, GetParam().channels);
  EXPECT_DOUBLE_EQ(motion.frame_rate, 1.0 / GetParam().frame_time);
  EXPECT_TRUE(skeleton.has_translation_channels(0));
  EXPECT_TRUE(ValidateMotion(skeleton, motion).ok());
  for (int f = 1; f < motion.num_frames(); ++f) {
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      ASSERT_GE(motion.frames[f].rotations[j].dot(motion.frames[f - 1].rotations[j]), 0.0)
          << "frame " << f << " joint " << skeleton.name(j);
    }
  }
}

// 16_15's root OFFSET equals its first frame's position channels: the file only makes
// sense if position channels replace the offset (rather than add to it).
TEST(BvhRealDataFacts, RootOffsetOf16_15IsTheFirstFramePosition) {
  MOCAPSOLVE_DATA_FILE(path, "bvh/16_15.bvh");
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadBvh(path, &skeleton, &motion).ok());
  EXPECT_EQ(skeleton.offset(0), Eigen::Vector3d(6.939, 97.422, -151.953));
  EXPECT_EQ(motion.frames[0].translations[0], skeleton.offset(0));
  EXPECT_EQ(skeleton.name(0), "root");
}

// 131_01 mixes orders: the legs and spine are ZYX, the arm chain (hand-edited lines with
// LF endings in a CRLF file) is ZXY.
TEST(BvhRealDataFacts, MixedRotationOrdersIn131_01) {
  MOCAPSOLVE_DATA_FILE(path, "bvh/131_01.bvh");
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadBvh(path, &skeleton, &motion).ok());
  const std::vector<Channel> zyx = {Channel::kZrotation, Channel::kYrotation, Channel::kXrotation};
  const std::vector<Channel> zxy = {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
  const int hip = skeleton.FindJoint("LeftHip");
  const int shoulder = skeleton.FindJoint("LeftShoulder");
  ASSERT_GE(hip, 0);
  ASSERT_GE(shoulder, 0);
  EXPECT_EQ(skeleton.joint(hip).channels, zyx);
  EXPECT_EQ(skeleton.joint(shoulder).channels, zxy);
}

}  // namespace
}  // namespace mocapsolve
