// Hostile input (issue 15): the files of tests/data/bad/make_bad_hostile.py and their
// in-memory variants give one-line errors naming the file and the cause, cheaply.
#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "io/bvh_reader.h"
#include "io/bvh_writer.h"
#include "io/c3d_reader.h"
#include "io/c3d_writer.h"
#include "io/fbx_reader.h"
#include "io/gltf_reader.h"
#include "io/marker_set_file.h"
#include "io/trc_reader.h"
#include "kinematics/quote_token.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

std::string Bad(const std::string& name) { return testing::SourcePath("tests/data/bad/" + name); }

void ExpectOneLineError(const Status& status, const std::string& file, const std::string& part) {
  ASSERT_FALSE(status.ok()) << file;
  EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
  EXPECT_EQ(status.message().rfind(file, 0), 0u) << status.message();
  EXPECT_NE(status.message().find(part), std::string::npos)
      << "expected '" << part << "' in: " << status.message();
  EXPECT_LT(status.message().size(), 400u) << status.message();
}

TEST(HostileInput, GlbWithExtrasNested30000Deep) {
  const std::string path = Bad("bad_gltf_deep_extras.glb");
  GltfDocument document;
  ExpectOneLineError(GltfDocument::Read(path, &document), path, "nested more than 128 levels deep");
  // The same nesting as .gltf JSON text.
  const std::string json = "{\"asset\":{\"version\":\"2.0\",\"extras\":" + std::string(30000, '[') +
                           std::string(30000, ']') + "}}";
  ExpectOneLineError(GltfDocument::Parse(json, "deep.gltf", "", &document), "deep.gltf",
                     "glTF JSON nested more than");
}

// Found by the gltf fuzzer: keys 1e-39 s apart made the key rate 1e39 fps and the frame
// count overflow int (UBSan). Sampling rates above 1e6 fps are refused.
TEST(HostileInput, GltfKeysADenormalApart) {
  const std::string path = Bad("bad_gltf_key_rate.gltf");
  GltfDocument document;
  ASSERT_TRUE(GltfDocument::Read(path, &document).ok());
  GltfCharacter character;
  ASSERT_TRUE(ReadGltfCharacter(document, GltfReadOptions(), &character).ok());
  Motion motion;
  ExpectOneLineError(ReadGltfAnimation(document, character, GltfAnimationOptions(), &motion), path,
                     "frame rate 1e+39 (from the key spacing) is not in (0, 1e6] fps");
}

TEST(HostileInput, AsciiFbxWith30000NestedBraces) {
  const std::string path = Bad("bad_fbx_deep_braces.fbx");
  Skeleton skeleton;
  Motion motion;
  ExpectOneLineError(ReadFbx(path, {}, &skeleton, &motion), path, "nested more than 128 braces");
}

// An FBX whose Connections chain 12,000 models: no deep braces, but assimp's converter
// recurses once per level and overflows the stack (SIGSEGV in Debian's assimp 5.2.5).
// The forked child dies, this process reports it. 10,000 models already crash it; 5,000
// do not, and are refused by our own depth bound instead.
std::string FbxChain(int n) {
  std::string text = "; FBX 7.4.0 project file\nFBXHeaderExtension: {\nFBXVersion: 7400\n}\nObjects: {\n";
  for (int i = 1; i <= n; ++i) text += "Model: " + std::to_string(i) + ",\"Model::" + std::to_string(i) + "\",\"Null\"{\n}\n";
  text += "}\nConnections: {\nC: \"OO\",1,0\n";
  for (int i = 2; i <= n; ++i) text += "C: \"OO\"," + std::to_string(i) + "," + std::to_string(i - 1) + "\n";
  return text + "}\n";
}

TEST(HostileInput, FbxThatCrashesAssimpBecomesAnError) {
  Skeleton skeleton;
  Motion motion;
  const auto start = std::chrono::steady_clock::now();
  const Status status = ParseFbx(FbxChain(12000), "chain.fbx", {}, &skeleton, &motion);
  ExpectOneLineError(status, "chain.fbx", "assimp crashed parsing the file");
  std::printf("%s (%.2f s)\n", status.message().c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  ExpectOneLineError(ParseFbx(FbxChain(2000), "chain.fbx", {}, &skeleton, &motion), "chain.fbx",
                     "node hierarchy deeper than 1000 levels");
}

TEST(HostileInput, BvhFrameTimeDenormal) {
  const std::string path = Bad("bad_frame_time_tiny.bvh");
  Skeleton skeleton;
  Motion motion;
  ExpectOneLineError(ReadBvh(path, &skeleton, &motion), path, "frame time of 1e-6 to 1000 seconds");
}

TEST(HostileInput, BvhNested2000Deep) {
  const std::string path = Bad("bad_deep_nesting.bvh");
  Skeleton skeleton;
  Motion motion;
  ExpectOneLineError(ReadBvh(path, &skeleton, &motion), path, "nested at most 1000 deep");
}

// The cause of the `convert` hang: depth-many tabs per line. A chain at the depth limit
// now writes text linear in the joint count.
TEST(HostileInput, BvhWriterIsLinearInTheDepth) {
  std::vector<JointSpec> joints(kMaxSkeletonDepth + 1);
  for (int j = 0; j <= kMaxSkeletonDepth; ++j) {
    joints[j].name = "j" + std::to_string(j);
    joints[j].parent = j - 1;
    joints[j].offset = Eigen::Vector3d(0, 1, 0);
    joints[j].channels = {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
  }
  Skeleton skeleton;
  ASSERT_TRUE(Skeleton::Create(joints, {}, LengthUnit(), &skeleton).ok());
  Motion motion;
  motion.frame_rate = 30;
  motion.frames.push_back(RestPose(skeleton));
  const std::string text = FormatBvh(skeleton, motion);
  EXPECT_LT(text.size(), 400u * joints.size()) << text.size() << " bytes";
  Skeleton back;
  Motion back_motion;
  ASSERT_TRUE(ParseBvh(text, "deep.bvh", &back, &back_motion).ok());
  EXPECT_EQ(back.num_joints(), skeleton.num_joints());
  // One joint more is refused.
  joints.push_back(joints.back());
  joints.back().name = "one_too_deep";
  joints.back().parent = kMaxSkeletonDepth;
  const Status status = Skeleton::Create(joints, {}, LengthUnit(), &skeleton);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("nested deeper than 1000"), std::string::npos) << status.message();
}

TEST(HostileInput, TrcCoordinateBeyondSaneMagnitude) {
  const std::string path = Bad("bad_huge_coordinate.trc");
  MarkerTrajectories trajectories;
  ExpectOneLineError(ReadTrc(path, &trajectories), path, "column 4 (Y of 'LASI') '1e308' is beyond +-1e9");
}

TEST(HostileInput, DuplicateMarkerLabels) {
  MarkerTrajectories trajectories;
  const std::string trc = Bad("bad_duplicate_labels.trc");
  ExpectOneLineError(ReadTrc(trc, &trajectories), trc, "marker label 'LBWT' is used twice (markers 1 and 3)");
  // A C3D's repeated label is numbered instead (real Motion Analysis files carry them;
  // io/c3d_points.h), with a warning naming it.
  const std::string c3d = Bad("quirk_c3d_duplicate_labels.c3d");
  C3dFileInfo info;
  ASSERT_TRUE(ReadC3d(c3d, &trajectories, &info).ok());
  EXPECT_EQ(trajectories.labels(), (std::vector<std::string>{"LBWT", "RBWT", "LBWT#2"}));
  ASSERT_EQ(info.warnings.size(), 1u);
  EXPECT_NE(info.warnings[0].find("'LBWT' (points 1, 3 read as LBWT, LBWT#2)"), std::string::npos)
      << info.warnings[0];
}

TEST(HostileInput, C3dPointRateNanZeroNegative) {
  for (const char* name : {"bad_c3d_rate_nan.c3d", "bad_c3d_rate_zero.c3d", "bad_c3d_rate_negative.c3d"}) {
    const std::string path = Bad(name);
    MarkerTrajectories trajectories;
    ExpectOneLineError(ReadC3d(path, &trajectories), path, "POINT:RATE");
  }
}

TEST(HostileInput, C3dCoordinateBeyondSaneMagnitude) {
  MarkerTrajectories trajectories({"A"}, 1);
  trajectories.frame_rate = 100;
  trajectories.unit = LengthUnitFromName("mm");
  trajectories.SetSample(0, 0, Eigen::Vector3d(1, 0, 0));
  std::string bytes;
  ASSERT_TRUE(EncodeC3d(trajectories, "huge.c3d", &bytes).ok());
  // The writer refuses 1e38 (io/input_limits.h), so put it in the file: the first
  // float of the data (float storage; header word 9 is the data start block).
  const size_t data = (static_cast<std::uint8_t>(bytes[16]) + 256 * static_cast<std::uint8_t>(bytes[17]) - 1) * 512;
  const float huge = 1e38f;
  std::memcpy(&bytes[data], &huge, 4);
  MarkerTrajectories back;
  // As %g: "1e+38", not std::to_string's 39 digits.
  ExpectOneLineError(ParseC3d(bytes, "huge.c3d", &back), "huge.c3d", "coordinate 1e+38 beyond +-1e9");
}

// Values no writer can represent (io/input_limits.h), refused by the reader with the field.
TEST(HostileInput, RatesAndCoordinatesBeyondWhatWritersHold) {
  Skeleton skeleton;
  Motion motion;
  ExpectOneLineError(ReadBvh(Bad("bad_frame_time_huge.bvh"), &skeleton, &motion), Bad("bad_frame_time_huge.bvh"),
                     "expected a frame time of 1e-6 to 1000 seconds, got '1e308'");
  ExpectOneLineError(ReadBvh(Bad("bad_root_position_huge.bvh"), &skeleton, &motion),
                     Bad("bad_root_position_huge.bvh"),
                     "expected a number within +-1e9 (frame 2, joint 'Hips' Xposition), got '1e308'");
  MarkerTrajectories trajectories;
  ExpectOneLineError(ReadTrc(Bad("bad_trc_rate_huge.trc"), &trajectories), Bad("bad_trc_rate_huge.trc"),
                     "DataRate 1e+308 is outside 0.001..1e+06 Hz");
  ExpectOneLineError(ReadTrc(Bad("bad_trc_rate_denormal.trc"), &trajectories), Bad("bad_trc_rate_denormal.trc"),
                     "DataRate 1e-310 is outside 0.001..1e+06 Hz");
}

// 0 points and frames 1..2^31-1 in 1 KB: the data bounds nothing, kMaxFrames does.
TEST(HostileInput, C3dWithoutPointsClaimingBillionsOfFrames) {
  MarkerTrajectories trajectories;
  const auto start = std::chrono::steady_clock::now();
  ExpectOneLineError(ReadC3d(Bad("bad_c3d_no_points_huge_frames.c3d"), &trajectories),
                     Bad("bad_c3d_no_points_huge_frames.c3d"), "(2147483647) are more than the 16777216 a take may have");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

// A FIFO blocked `info` forever, /dev/zero never ends: the readers' common open path
// (ReadFileToString, through OpenRegularFile) refuses anything but a regular file, without
// opening it in a way that blocks; tinygltf's external buffers go through it too.
TEST(HostileInput, NonRegularFilesAreRefusedWithoutBlocking) {
  const std::string fifo = testing::TempPath("take.bvh");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  std::string bytes;
  ExpectOneLineError(ReadFileToString(fifo, &bytes), fifo, "is not a regular file (a FIFO)");
  Skeleton skeleton;
  Motion motion;
  ExpectOneLineError(ReadBvh(fifo, &skeleton, &motion), fifo, "is not a regular file (a FIFO)");
  ExpectOneLineError(ReadFileToString("/dev/zero", &bytes), "/dev/zero", "(a character device)");
  const std::string buffer_fifo = testing::TempPath("buffer.bin");
  ASSERT_EQ(::mkfifo(buffer_fifo.c_str(), 0600), 0);
  const std::string gltf = testing::TempPath("external.gltf");
  testing::WriteTextFile(gltf, "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"uri\": \"buffer.bin\", "
                               "\"byteLength\": 4}]}");
  GltfDocument document;
  EXPECT_FALSE(GltfDocument::Read(gltf, &document).ok());
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);
}

TEST(HostileInput, NamesInMessagesAreEscapedAndCut) {
  Skeleton skeleton;
  Motion motion;
  EXPECT_EQ(QuoteToken("a\nb"), "'a\\x0ab'");
  EXPECT_EQ(QuoteToken(std::string(20 << 20, 'J')), "'" + std::string(64, 'J') + "...'");
  for (const char* name : {"bad_markerset_newline_name.json", "bad_markerset_long_name.json"}) {
    const std::string path = Bad(name);
    std::string bvh =
        "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 3 Xposition Yposition Zposition\nEnd Site\n{\n"
        "OFFSET 0 1 0\n}\n}\nMOTION\nFrames: 1\nFrame Time: 0.01\n0 0 0\n";
    ASSERT_TRUE(ParseBvh(bvh, "tiny.bvh", &skeleton, &motion).ok());
    MarkerSet markers;
    ExpectOneLineError(ReadMarkerSet(path, skeleton, &markers), path, "unknown joint '");
  }
}

}  // namespace
}  // namespace mocapsolve
