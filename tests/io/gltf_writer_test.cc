#include "io/gltf_writer.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "io/gltf_reader.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// The file's first clip, changed so that it is no longer any clip of the file: every
// joint turned by a frame-dependent rotation, the root moved, at 50 fps.
Motion NewMotion(const GltfDocument& doc, const GltfCharacter& c) {
  Motion m;
  GltfAnimationOptions options;
  EXPECT_TRUE(ReadGltfAnimation(doc, c, options, &m).ok());
  m.frame_rate = 50.0;
  for (int f = 0; f < m.num_frames(); ++f) {
    for (int j = 0; j < c.skeleton.num_joints(); ++j) {
      const Eigen::Vector3d v(0.3 * std::sin(0.1 * f + j), 0.2 * std::cos(0.07 * f * j), 0.1);
      m.frames[f].rotations[j] = (m.frames[f].rotations[j] * ExpMap(v)).normalized();
    }
    m.frames[f].translations[0] += Eigen::Vector3d(0.01 * f, 0.0, -0.02 * f);
  }
  MakeSignContinuous(&m);
  return m;
}

// Poses equal as rotations and translations; float storage gives ~6e-8 relative.
void ExpectSameMotion(const Motion& a, const Motion& b, double length_scale) {
  ASSERT_EQ(a.num_frames(), b.num_frames());
  EXPECT_DOUBLE_EQ(a.frame_rate, b.frame_rate);
  for (int f = 0; f < a.num_frames(); ++f) {
    for (size_t j = 0; j < a.frames[f].rotations.size(); ++j) {
      // 1e-6 rad and 1e-6 of the character's size: float32 keys.
      ASSERT_LT(a.frames[f].rotations[j].angularDistance(b.frames[f].rotations[j]), 1e-6)
          << "frame " << f << " joint " << j;
      ASSERT_LT((a.frames[f].translations[j] - b.frames[f].translations[j]).norm(),
                1e-6 * (length_scale + a.frames[f].translations[j].norm()))
          << "frame " << f << " joint " << j;
    }
  }
}

class GltfRoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(GltfRoundTrip, AddedAnimationReadsBackAsWritten) {
  MOCAPSOLVE_DATA_FILE(path, std::string("gltf/") + GetParam());
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Read(path, &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  const Motion motion = NewMotion(doc, c);
  double size = 0.0;
  for (int j = 0; j < c.skeleton.num_joints(); ++j) size = std::max(size, c.skeleton.offset(j).norm());
  for (const char* ext : {".glb", ".gltf"}) {
    const std::string out = testing::TempPath(std::string("retargeted") + ext);
    Status status = WriteGltfWithAnimation(doc, c, motion, "mocapsolve", out);
    ASSERT_TRUE(status.ok()) << status.message();
    GltfDocument back_doc;
    status = GltfDocument::Read(out, &back_doc);
    ASSERT_TRUE(status.ok()) << status.message();
    GltfCharacter back;
    status = ReadGltfCharacter(back_doc, {}, &back);
    ASSERT_TRUE(status.ok()) << status.message();
    // Same character: joints, offsets, mesh.
    ASSERT_EQ(back.skeleton.num_joints(), c.skeleton.num_joints());
    for (int j = 0; j < c.skeleton.num_joints(); ++j) {
      EXPECT_EQ(back.skeleton.name(j), c.skeleton.name(j));
      EXPECT_LT((back.skeleton.offset(j) - c.skeleton.offset(j)).norm(), 1e-12 * (1 + size));
    }
    EXPECT_EQ(back.mesh.num_vertices(), c.mesh.num_vertices());
    EXPECT_EQ(back.triangles, c.triangles);
    ASSERT_EQ(back.animation_names.size(), c.animation_names.size() + 1);
    EXPECT_EQ(back.animation_names.back(), "mocapsolve");
    // The new clip samples back to the written poses at the written rate.
    Motion read;
    GltfAnimationOptions options;
    options.animation = "mocapsolve";
    status = ReadGltfAnimation(back_doc, back, options, &read);
    ASSERT_TRUE(status.ok()) << status.message();
    ExpectSameMotion(motion, read, size);
    // The original clips are untouched.
    Motion original, original_back;
    ASSERT_TRUE(ReadGltfAnimation(doc, c, {}, &original).ok());
    ASSERT_TRUE(ReadGltfAnimation(back_doc, back, {}, &original_back).ok());
    ExpectSameMotion(original, original_back, size);
  }
}

INSTANTIATE_TEST_SUITE_P(SharedData, GltfRoundTrip,
                         ::testing::Values("CesiumMan.glb", "RiggedFigure.glb", "Xbot.glb", "Ely.glb",
                                           "Soldier.glb", "RobotExpressive.glb", "Fox.glb"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           return name.substr(0, name.find('.'));
                         });

TEST(GltfWriter, RefusesBadRequests) {
  MOCAPSOLVE_DATA_FILE(path, "gltf/CesiumMan.glb");
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Read(path, &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  Motion motion = NewMotion(doc, c);
  const std::string out = testing::TempPath("bad.glb");
  // An empty name, a name the file already uses (CesiumMan's clip is unnamed: ""), a bad
  // rate, a pose of the wrong size, a wrong extension: each an error, no file written.
  EXPECT_FALSE(WriteGltfWithAnimation(doc, c, motion, "", out).ok());
  Motion bad = motion;
  bad.frame_rate = 0.0;
  EXPECT_FALSE(WriteGltfWithAnimation(doc, c, bad, "x", out).ok());
  bad = motion;
  bad.frames[1].rotations.pop_back();
  EXPECT_FALSE(WriteGltfWithAnimation(doc, c, bad, "x", out).ok());
  bad = motion;
  bad.frames[2].translations[0].x() = std::nan("");
  EXPECT_FALSE(WriteGltfWithAnimation(doc, c, bad, "x", out).ok());
  const Status status = WriteGltfWithAnimation(doc, c, motion, "x", testing::TempPath("x.bvh"));
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find(".glb or .gltf"), std::string::npos) << status.message();
  EXPECT_FALSE(testing::FileExists(out));
  // Writing the same name twice into one output: the second write sees the first.
  ASSERT_TRUE(WriteGltfWithAnimation(doc, c, motion, "x", out).ok());
  GltfDocument written;
  ASSERT_TRUE(GltfDocument::Read(out, &written).ok());
  GltfCharacter wc;
  ASSERT_TRUE(ReadGltfCharacter(written, {}, &wc).ok());
  const Status twice = WriteGltfWithAnimation(written, wc, motion, "x", testing::TempPath("y.glb"));
  EXPECT_FALSE(twice.ok());
  EXPECT_NE(twice.message().find("already has an animation named 'x'"), std::string::npos) << twice.message();
}

}  // namespace
}  // namespace mocapsolve
