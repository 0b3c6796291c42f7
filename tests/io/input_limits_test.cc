#include "io/input_limits.h"

#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/bvh_reader.h"
#include "io/bvh_writer.h"
#include "io/c3d_reader.h"
#include "io/c3d_writer.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/trc_reader.h"
#include "io/trc_writer.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

TEST(JsonNestingDepth, CountsBracketsOutsideStrings) {
  EXPECT_EQ(JsonNestingDepth(""), 0);
  EXPECT_EQ(JsonNestingDepth("1"), 0);
  EXPECT_EQ(JsonNestingDepth("{\"a\": [1, {\"b\": []}]}"), 4);
  // Brackets inside strings, also after an escaped quote, do not count.
  EXPECT_EQ(JsonNestingDepth("{\"[[[\\\"{{{\": 1}"), 1);
  // Unbalanced closers never make the depth negative.
  EXPECT_EQ(JsonNestingDepth("]]]]{"), 1);
}

TEST(JsonNestingDepth, StopsPastTheLimit) {
  const std::string deep = std::string(30000, '[') + std::string(30000, ']');
  EXPECT_EQ(JsonNestingDepth(deep), kMaxThirdPartyNesting + 1);
  EXPECT_EQ(JsonNestingDepth(deep, 10), 11);
  EXPECT_EQ(JsonNestingDepth(std::string(128, '[')), 128);
}

TEST(FbxBraceDepth, CountsBracesOutsideStringsAndComments) {
  EXPECT_EQ(FbxBraceDepth("; FBX 7.4.0 project file {{{{\nObjects: {\n Model: 1, \"M::{{\", \"\" {\n }\n}\n"), 2);
  // A quote does not run past its line: the next line's braces count again.
  EXPECT_EQ(FbxBraceDepth("A: \"open\n{ {\n}}"), 2);
  const std::string deep = std::string(30000, '{');
  EXPECT_EQ(FbxBraceDepth(deep), kMaxThirdPartyNesting + 1);
}


// Writers validate what readers validate: every writer refuses a rate or coordinate just
// beyond io/input_limits.h's bounds, naming the field, and a take at the bounds reads
// back. (A TRC rate of 1e308 became a C3D rate of NaN, 1e-310 one of 0; a BVH frame time
// of 1e308 a glTF time accessor whose "max" was null.)
using ::testing::HasSubstr;

constexpr double kJustOver = 1.0 + 1e-9;

MarkerTrajectories TwoFrameTake(double rate, double coordinate) {
  MarkerTrajectories take({"A", "B"}, 2);
  take.frame_rate = rate;
  take.unit = LengthUnitFromName("mm");
  take.SetSample(0, 0, Eigen::Vector3d(coordinate, -coordinate, 1.0));
  take.SetSample(1, 1, Eigen::Vector3d(0.5, 2.0, -coordinate));
  return take;
}

void ExpectRefused(const Status& status, const std::string& field) {
  ASSERT_FALSE(status.ok()) << field;
  EXPECT_THAT(status.message(), HasSubstr(field));
  EXPECT_EQ(status.message().find('\n'), std::string::npos);
}

TEST(WriterBounds, MarkerWritersRefuseValuesJustOutOfRange) {
  std::string bytes;
  for (int format = 0; format < 2; ++format) {
    const auto write = [&](const MarkerTrajectories& take) {
      return format == 0 ? EncodeC3d(take, "out.c3d", &bytes) : FormatTrc(take, "out.trc", &bytes);
    };
    ExpectRefused(write(TwoFrameTake(kMaxFrameRate * kJustOver, 1.0)), "frame rate 1e+06 is outside");
    ExpectRefused(write(TwoFrameTake(kMinFrameRate / kJustOver, 1.0)), "frame rate 0.001 is outside");
    ExpectRefused(write(TwoFrameTake(1e308, 1.0)), "frame rate 1e+308");
    ExpectRefused(write(TwoFrameTake(1e-310, 1.0)), "frame rate 1e-310");
    ExpectRefused(write(TwoFrameTake(100.0, kMaxCoordinate * kJustOver)), "frame 0, marker 'A': 1e+09 is beyond");
  }
}

TEST(WriterBounds, MarkerFormatsRoundTripAtTheBounds) {
  for (double rate : {kMinFrameRate, kMaxFrameRate}) {
    const MarkerTrajectories take = TwoFrameTake(rate, kMaxCoordinate);
    std::string bytes;
    MarkerTrajectories back;
    ASSERT_TRUE(EncodeC3d(take, "at.c3d", &bytes).ok()) << rate;
    Status status = ParseC3d(bytes, "at.c3d", &back);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_TRUE(CheckMarkerBounds(back).ok()) << rate;
    EXPECT_NEAR(back.frame_rate, rate, 1e-7 * rate);
    EXPECT_DOUBLE_EQ(back.position(0, 0).x(), kMaxCoordinate);
    ASSERT_TRUE(FormatTrc(take, "at.trc", &bytes).ok()) << rate;
    status = ParseTrc(bytes, "at.trc", &back);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_TRUE(CheckMarkerBounds(back).ok()) << rate;
    EXPECT_NEAR(back.frame_rate, rate, 1e-9 * rate);
    EXPECT_DOUBLE_EQ(back.position(1, 1).z(), -kMaxCoordinate);
  }
}

// A root with position and rotation channels and one child, two frames.
void TwoJointMotion(double rate, double root_x, Skeleton* skeleton, Motion* motion) {
  std::vector<JointSpec> joints(2);
  joints[0].name = "Hips";
  joints[0].channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition,
                        Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
  joints[1].name = "Spine";
  joints[1].parent = 0;
  joints[1].offset = Eigen::Vector3d(0.0, 10.0, 0.0);
  joints[1].channels = {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
  ASSERT_TRUE(Skeleton::Create(joints, {}, LengthUnit(), skeleton).ok());
  motion->frame_rate = rate;
  motion->frames.assign(2, RestPose(*skeleton));
  motion->frames[1].translations[0].x() = root_x;
}

TEST(WriterBounds, BvhWriterRefusesValuesJustOutOfRangeAndRoundTripsAtTheBounds) {
  Skeleton skeleton;
  Motion motion;
  TwoJointMotion(kMaxFrameRate * kJustOver, 1.0, &skeleton, &motion);
  ExpectRefused(CheckBvhWritable(skeleton, motion, {}), "frame rate 1e+06 is outside");
  TwoJointMotion(kMinFrameRate / kJustOver, 1.0, &skeleton, &motion);
  ExpectRefused(CheckBvhWritable(skeleton, motion, {}), "frame rate 0.001 is outside");
  TwoJointMotion(100.0, kMaxCoordinate * kJustOver, &skeleton, &motion);
  ExpectRefused(CheckBvhWritable(skeleton, motion, {}), "frame 1, joint 'Hips' translation: 1e+09 is beyond");
  BvhWriteOptions scaled;
  scaled.scale = 10.0;  // In range before the writer's unit change, not after.
  TwoJointMotion(100.0, kMaxCoordinate / 2, &skeleton, &motion);
  ExpectRefused(CheckBvhWritable(skeleton, motion, scaled), "joint 'Hips' translation");
  for (double rate : {kMinFrameRate, kMaxFrameRate}) {
    TwoJointMotion(rate, -kMaxCoordinate, &skeleton, &motion);
    ASSERT_TRUE(CheckBvhWritable(skeleton, motion, {}).ok()) << rate;
    Skeleton back_skeleton;
    Motion back;
    const Status status = ParseBvh(FormatBvh(skeleton, motion, {}), "at.bvh", &back_skeleton, &back);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_TRUE(CheckMotionBounds(back_skeleton, back).ok()) << rate;
    EXPECT_NEAR(back.frame_rate, rate, 1e-9 * rate);
    EXPECT_DOUBLE_EQ(back.frames[1].translations[0].x(), -kMaxCoordinate);
  }
}

TEST(WriterBounds, GltfWriterRefusesValuesJustOutOfRangeAndRoundTripsAtTheBounds) {
  GltfDocument document;
  ASSERT_TRUE(GltfDocument::Read(testing::SourcePath("tests/data/good/skinned.glb"), &document).ok());
  GltfCharacter character;
  ASSERT_TRUE(ReadGltfCharacter(document, {}, &character).ok());
  Motion motion;
  motion.frames.assign(2, character.rest_pose);
  std::string bytes;
  const auto write = [&](double rate, double root_x) {
    motion.frame_rate = rate;
    motion.frames[1].translations[0].x() = root_x;
    return SerializeGltfWithAnimation(document, character, motion, "bounds", true, &bytes);
  };
  ExpectRefused(write(kMaxFrameRate * kJustOver, 0.0), "frame rate 1e+06 is outside");
  ExpectRefused(write(1e-308, 0.0), "frame rate 1e-308 is outside");
  ExpectRefused(write(100.0, kMaxCoordinate * kJustOver), "translation: 1e+09 is beyond");
  for (double rate : {kMinFrameRate, kMaxFrameRate}) {
    Status status = write(rate, kMaxCoordinate);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(bytes.find("null"), std::string::npos) << "no non-finite number in the JSON";
    GltfDocument back_document;
    status = GltfDocument::Parse(bytes, "at.glb", ".", &back_document);
    ASSERT_TRUE(status.ok()) << status.message();
    GltfCharacter back_character;
    ASSERT_TRUE(ReadGltfCharacter(back_document, {}, &back_character).ok());
    GltfAnimationOptions options;
    options.animation = "bounds";
    Motion back;
    status = ReadGltfAnimation(back_document, back_character, options, &back);
    ASSERT_TRUE(status.ok()) << status.message();
    const Status bounds = CheckMotionBounds(back_character.skeleton, back);
    EXPECT_TRUE(bounds.ok()) << rate << ": " << bounds.message();
    EXPECT_NEAR(back.frame_rate, rate, 1e-6 * rate);
    EXPECT_EQ(back.num_frames(), 2);
  }
}

TEST(ReadBounds, ShortNumbersInMessages) {
  const Status status = CheckCoordinates(Eigen::Vector3d(0.0, 1e38, 0.0), "marker 'A'");
  EXPECT_EQ(status.message(), "marker 'A': 1e+38 is beyond +-1e+09");  // Not 40 digits.
  EXPECT_TRUE(CheckUnitScale(0.0, "scale").ok());
  ExpectRefused(CheckUnitScale(1e308, "marker_files.scale"), "marker_files.scale: 1e+308 is outside");
}

}  // namespace
}  // namespace mocapsolve
