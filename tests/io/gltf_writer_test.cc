#include "io/gltf_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "io/atomic_file.h"
#include "io/gltf_reader.h"
#include "kinematics/rotation.h"
#include "tests/gltf_test_files.h"
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
    // The new clip first (the one readers open by default), the character's own after it.
    ASSERT_EQ(back.animation_names.size(), c.animation_names.size() + 1);
    EXPECT_EQ(back.animation_names.front(), "mocapsolve");
    for (size_t a = 0; a < c.animation_names.size(); ++a) {
      EXPECT_EQ(back.animation_names[a + 1], c.animation_names[a]);
    }
    // The new clip samples back to the written poses at the written rate.
    Motion read;
    GltfAnimationOptions options;
    options.animation = "mocapsolve";
    status = ReadGltfAnimation(back_doc, back, options, &read);
    ASSERT_TRUE(status.ok()) << status.message();
    ExpectSameMotion(motion, read, size);
    // A reader's default clip is the new one.
    Motion default_clip;
    ASSERT_TRUE(ReadGltfAnimation(back_doc, back, {}, &default_clip).ok());
    ExpectSameMotion(motion, default_clip, size);
    // The original clips are untouched.
    if (c.animation_names.empty()) continue;
    Motion original, original_back;
    ASSERT_TRUE(ReadGltfAnimation(doc, c, {}, &original).ok());
    GltfAnimationOptions first_own;
    first_own.animation = "1";  // By index: a source's clip may be unnamed.
    ASSERT_TRUE(ReadGltfAnimation(back_doc, back, first_own, &original_back).ok());
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

// The bytes of an accessor the writer made (tightly packed: no byte stride).
std::string AccessorBytes(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& a = model.accessors.at(index);
  const tinygltf::BufferView& view = model.bufferViews.at(a.bufferView);
  EXPECT_EQ(view.byteStride, 0);
  const size_t size = a.count * tinygltf::GetComponentSizeInBytes(a.componentType) *
                      tinygltf::GetNumComponentsInType(a.type);
  const std::vector<unsigned char>& data = model.buffers.at(view.buffer).data;
  const size_t start = view.byteOffset + a.byteOffset;
  EXPECT_LE(start + size, data.size());
  return std::string(reinterpret_cast<const char*>(data.data()) + start, size);
}

// --animation_only: the skeleton's nodes (names, rest transforms, hierarchy), the skin
// and the new animation, no meshes or images; the animation's channels are the full
// file's, key for key, on the nodes of the same names; a fraction of the size.
class GltfAnimationOnly : public ::testing::TestWithParam<const char*> {};

TEST_P(GltfAnimationOnly, HoldsTheSkeletonSkinAndAnimationOnly) {
  MOCAPSOLVE_DATA_FILE(path, std::string("gltf/") + GetParam());
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Read(path, &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  Motion motion = NewMotion(doc, c);
  const int still = c.skeleton.num_joints() - 1;  // A leaf held still: its channel gets one key.
  for (Pose& pose : motion.frames) pose.rotations[still] = motion.frames[0].rotations[still];
  GltfWriteOptions animation_only;
  animation_only.animation_only = true;
  std::string full_bytes, slim_bytes;
  ASSERT_TRUE(SerializeGltfWithAnimation(doc, c, motion, "mocapsolve", true, &full_bytes).ok());
  Status status = SerializeGltfWithAnimation(doc, c, motion, "mocapsolve", true, &slim_bytes, animation_only);
  ASSERT_TRUE(status.ok()) << status.message();
  GltfDocument full_doc, slim_doc;
  ASSERT_TRUE(GltfDocument::Parse(full_bytes, "full.glb", "", &full_doc).ok());
  status = GltfDocument::Parse(slim_bytes, "slim.glb", "", &slim_doc);
  ASSERT_TRUE(status.ok()) << status.message();
  const tinygltf::Model& full = full_doc.model();
  const tinygltf::Model& slim = slim_doc.model();
  std::printf("%s: full %zu bytes, animation only %zu bytes (%.1f %%), %d frames\n", GetParam(), full_bytes.size(),
              slim_bytes.size(), 100.0 * slim_bytes.size() / full_bytes.size(), motion.num_frames());
  EXPECT_TRUE(slim.meshes.empty());
  EXPECT_TRUE(slim.materials.empty());
  EXPECT_TRUE(slim.textures.empty());
  EXPECT_TRUE(slim.images.empty());
  EXPECT_TRUE(slim.samplers.empty());
  EXPECT_TRUE(slim.cameras.empty());
  EXPECT_TRUE(slim.extensionsRequired.empty());
  EXPECT_EQ(slim.buffers.size(), 1u);
  ASSERT_EQ(slim.scenes.size(), 1u);
  ASSERT_EQ(slim.animations.size(), 1u);
  EXPECT_EQ(slim.animations[0].name, "mocapsolve");
  // The nodes: skin joint k is the full file's skin joint k, a kept node's parent the
  // full node's parent (names may repeat: RobotExpressive has a mesh node and a joint both
  // named "Torso"); each with the full node's name and rest transform.
  ASSERT_EQ(slim.skins.size(), 1u);
  const tinygltf::Skin& skin = slim.skins[0];
  const tinygltf::Skin& full_skin = full.skins[c.skin];
  ASSERT_EQ(skin.joints.size(), full_skin.joints.size());
  std::vector<int> slim_parent(slim.nodes.size(), -1), full_parent(full.nodes.size(), -1);
  for (size_t n = 0; n < slim.nodes.size(); ++n) {
    EXPECT_EQ(slim.nodes[n].mesh, -1);
    EXPECT_EQ(slim.nodes[n].skin, -1);
    for (int child : slim.nodes[n].children) slim_parent.at(child) = static_cast<int>(n);
  }
  for (size_t n = 0; n < full.nodes.size(); ++n) {
    for (int child : full.nodes[n].children) full_parent.at(child) = static_cast<int>(n);
  }
  std::vector<int> full_of(slim.nodes.size(), -1);  // Slim node -> full node.
  for (size_t k = 0; k < skin.joints.size(); ++k) {
    for (int a = skin.joints[k], b = full_skin.joints[k]; a >= 0; a = slim_parent[a], b = full_parent[b]) {
      ASSERT_GE(b, 0) << "slim node " << a << " has a parent the full file's node has not";
      if (full_of[a] >= 0) {
        EXPECT_EQ(full_of[a], b) << "slim node " << a;
        break;
      }
      full_of[a] = b;
    }
  }
  for (size_t n = 0; n < slim.nodes.size(); ++n) {
    const tinygltf::Node& node = slim.nodes[n];
    const int f = full_of[n];
    ASSERT_GE(f, 0) << "slim node " << n << " (" << node.name << ") is neither a joint nor above one";
    EXPECT_EQ(node.name, full.nodes[f].name);
    EXPECT_EQ(node.translation, full.nodes[f].translation) << node.name;
    EXPECT_EQ(node.rotation, full.nodes[f].rotation) << node.name;
    EXPECT_EQ(node.scale, full.nodes[f].scale) << node.name;
    EXPECT_EQ(node.matrix, full.nodes[f].matrix) << node.name;
    if (slim_parent[n] < 0) {
      EXPECT_EQ(full_parent[f], -1) << node.name;
      EXPECT_NE(std::find(slim.scenes[0].nodes.begin(), slim.scenes[0].nodes.end(), static_cast<int>(n)),
                slim.scenes[0].nodes.end()) << node.name;
    }
  }
  if (full_skin.inverseBindMatrices >= 0) {
    ASSERT_GE(skin.inverseBindMatrices, 0);
    const tinygltf::Accessor& ibm = full.accessors[full_skin.inverseBindMatrices];
    if (full.bufferViews[ibm.bufferView].byteStride == 0 && !ibm.sparse.isSparse) {
      EXPECT_EQ(AccessorBytes(slim, skin.inverseBindMatrices), AccessorBytes(full, full_skin.inverseBindMatrices));
    }
  }
  // The animation: channel k is the full file's channel k on the same node, key for key,
  // or, when all the full channel's keys are equal, its one key at time 0.
  const tinygltf::Animation& a = slim.animations[0];
  const tinygltf::Animation& b = full.animations.front();
  ASSERT_EQ(b.name, "mocapsolve");
  ASSERT_EQ(a.channels.size(), b.channels.size());
  int single_key_channels = 0;
  EXPECT_GE(a.channels.size(), static_cast<size_t>(c.skeleton.num_joints() - 1));
  for (size_t k = 0; k < a.channels.size(); ++k) {
    const tinygltf::AnimationChannel& ca = a.channels[k];
    const tinygltf::AnimationChannel& cb = b.channels[k];
    EXPECT_EQ(full_of.at(ca.target_node), cb.target_node) << "channel " << k;
    EXPECT_EQ(ca.target_path, cb.target_path);
    const tinygltf::AnimationSampler& sa = a.samplers.at(ca.sampler);
    const tinygltf::AnimationSampler& sb = b.samplers.at(cb.sampler);
    EXPECT_EQ(sa.interpolation, sb.interpolation);
    const std::string full_output = AccessorBytes(full, sb.output);
    if (slim.accessors[sa.input].count == 1 && full.accessors[sb.input].count > 1) {
      ++single_key_channels;
      EXPECT_EQ(slim.accessors[sa.input].minValues, std::vector<double>{0.0});
      const std::string key = AccessorBytes(slim, sa.output);
      ASSERT_EQ(slim.accessors[sa.output].count, 1u);
      for (size_t e = 0; e < full_output.size(); e += key.size()) {
        ASSERT_EQ(full_output.substr(e, key.size()), key) << "channel " << k << " key " << e / key.size();
      }
      continue;
    }
    EXPECT_EQ(AccessorBytes(slim, sa.input), AccessorBytes(full, sb.input));
    EXPECT_EQ(AccessorBytes(slim, sa.output), full_output) << "channel " << k;
    EXPECT_EQ(slim.accessors[sa.input].minValues, full.accessors[sb.input].minValues);
    EXPECT_EQ(slim.accessors[sa.input].maxValues, full.accessors[sb.input].maxValues);
  }
  // NewMotion turns every joint but `still` (a translation channel may be constant too).
  std::printf("%s: %d of %zu channels with one key\n", GetParam(), single_key_channels, a.channels.size());
  EXPECT_GE(single_key_channels, 1);
  EXPECT_LT(single_key_channels, static_cast<int>(a.channels.size()));
  // Read back (a character without vertices): the same skeleton, and the written motion.
  GltfCharacter back;
  status = ReadGltfCharacter(slim_doc, {}, &back);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(back.mesh.num_vertices(), 0);
  double size = 0.0;
  for (int j = 0; j < c.skeleton.num_joints(); ++j) size = std::max(size, c.skeleton.offset(j).norm());
  ASSERT_EQ(back.skeleton.num_joints(), c.skeleton.num_joints());
  for (int j = 0; j < c.skeleton.num_joints(); ++j) {
    EXPECT_EQ(back.skeleton.name(j), c.skeleton.name(j));
    EXPECT_EQ(back.skeleton.parent(j), c.skeleton.parent(j));
    // 1e-12: the same node transforms, composed the same way.
    EXPECT_LT((back.skeleton.offset(j) - c.skeleton.offset(j)).norm(), 1e-12 * (1 + size));
    EXPECT_LT(back.bind_pose.rotations[j].angularDistance(c.bind_pose.rotations[j]), 1e-12);
  }
  Motion read;
  status = ReadGltfAnimation(slim_doc, back, {}, &read);
  ASSERT_TRUE(status.ok()) << status.message();
  ExpectSameMotion(motion, read, size);
  EXPECT_LT(slim_bytes.size(), full_bytes.size());
  // Xbot: 5.2 MB of meshes against 65 joints' keys.
  if (std::string(GetParam()) == "Xbot.glb") {
    EXPECT_LT(slim_bytes.size(), full_bytes.size() / 10);
  }
  // The .gltf form (embedded buffer) parses too.
  std::string text;
  ASSERT_TRUE(SerializeGltfWithAnimation(doc, c, motion, "mocapsolve", false, &text, animation_only).ok());
  GltfDocument text_doc;
  status = GltfDocument::Parse(text, "slim.gltf", "", &text_doc);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(text_doc.model().nodes.size(), slim.nodes.size());
  EXPECT_TRUE(text_doc.model().meshes.empty());
}

INSTANTIATE_TEST_SUITE_P(SharedData, GltfAnimationOnly,
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

// Joint nodes given by a `matrix` (allowed by glTF, not animatable) read the same as
// TRS nodes and are rewritten as TRS by the writer; the clip round-trips.
TEST(GltfWriter, MatrixJointNodesAreReadAndRewrittenAsTrs) {
  MOCAPSOLVE_DATA_FILE(path, "gltf/CesiumMan.glb");
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Read(path, &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  tinygltf::Model model = doc.model();
  for (int n : model.skins[0].joints) {
    tinygltf::Node& node = model.nodes[n];
    Eigen::Affine3d a = Eigen::Affine3d::Identity();
    if (node.translation.size() == 3) a.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4) a.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized());
    if (node.scale.size() == 3) a.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
    node.matrix.assign(a.matrix().data(), a.matrix().data() + 16);  // Column-major, as glTF.
    node.translation.clear();
    node.rotation.clear();
    node.scale.clear();
  }
  tinygltf::TinyGLTF writer;
  std::ostringstream stream;
  ASSERT_TRUE(writer.WriteGltfSceneToStream(&model, stream, false, true));
  GltfDocument matrix_doc;
  Status status = GltfDocument::Parse(stream.str(), "matrix.glb", "", &matrix_doc);
  ASSERT_TRUE(status.ok()) << status.message();
  GltfCharacter mc;
  ASSERT_TRUE(ReadGltfCharacter(matrix_doc, {}, &mc).ok());
  ASSERT_EQ(mc.skeleton.num_joints(), c.skeleton.num_joints());
  for (int j = 0; j < c.skeleton.num_joints(); ++j) {
    // 1e-12: the matrix holds the same TRS composed in double.
    EXPECT_LT((mc.skeleton.offset(j) - c.skeleton.offset(j)).norm(), 1e-12);
    EXPECT_LT(mc.rest_pose.rotations[j].angularDistance(c.rest_pose.rotations[j]), 1e-12);
  }
  const Motion motion = NewMotion(doc, c);
  std::string bytes;
  status = SerializeGltfWithAnimation(matrix_doc, mc, motion, "from_matrix", true, &bytes);
  ASSERT_TRUE(status.ok()) << status.message();
  GltfDocument back;
  ASSERT_TRUE(GltfDocument::Parse(bytes, "back.glb", "", &back).ok());
  for (int n : back.model().skins[0].joints) {
    EXPECT_TRUE(back.model().nodes[n].matrix.empty());
    EXPECT_EQ(back.model().nodes[n].rotation.size(), 4u);
  }
  GltfCharacter bc;
  ASSERT_TRUE(ReadGltfCharacter(back, {}, &bc).ok());
  Motion read;
  GltfAnimationOptions options;
  options.animation = "from_matrix";
  ASSERT_TRUE(ReadGltfAnimation(back, bc, options, &read).ok());
  ExpectSameMotion(motion, read, 1.0);
}

// The pages' compact variant: int16 rotations, and a joint the motion holds still written
// as one key; it reads back as the motion (to int16 precision), every frame.
TEST(GltfWriter, CompactVariantHoldsConstantChannelsWithOneKey) {
  MOCAPSOLVE_DATA_FILE(path, "gltf/Xbot.glb");
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Read(path, &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  Motion motion;
  motion.frame_rate = 30.0;
  const int nj = c.skeleton.num_joints();
  for (int f = 0; f < 40; ++f) {
    Pose pose = c.rest_pose;
    for (int j = 0; j < nj; j += 2) pose.rotations[j] = pose.rotations[j] * ExpMap(Eigen::Vector3d(0.02 * f, 0.1, 0));
    pose.translations[0] += Eigen::Vector3d(0.01 * f, 0, 0);
    motion.frames.push_back(pose);
  }
  std::string full, compact;
  ASSERT_TRUE(SerializeGltfWithAnimation(doc, c, motion, "take", true, &full).ok());
  GltfWriteOptions page;
  page.compact = true;
  Status status = SerializeGltfWithAnimation(doc, c, motion, "take", true, &compact, page);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_LT(compact.size(), full.size());
  GltfDocument back;
  ASSERT_TRUE(GltfDocument::Parse(compact, "compact.glb", "", &back).ok());
  const tinygltf::Animation& animation = back.model().animations.front();
  int one_key = 0;
  for (const tinygltf::AnimationSampler& sampler : animation.samplers) {
    if (back.model().accessors[sampler.input].count == 1) ++one_key;
  }
  EXPECT_EQ(one_key, nj / 2);  // The odd joints' rotations.
  GltfCharacter bc;
  ASSERT_TRUE(ReadGltfCharacter(back, {}, &bc).ok());
  GltfAnimationOptions options;
  options.animation = "take";
  Motion read;
  status = ReadGltfAnimation(back, bc, options, &read);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(read.num_frames(), motion.num_frames());
  for (int f = 0; f < motion.num_frames(); ++f) {
    for (int j = 0; j < nj; ++j) {
      // 2e-4 rad: normalized int16 components (3e-5 each).
      ASSERT_LT(read.frames[f].rotations[j].angularDistance(motion.frames[f].rotations[j]), 2e-4)
          << "frame " << f << " joint " << j;
    }
  }
}

// A long clip's rate and frame count read back as written: float key times near the end
// of a 23 s clip are ~2e-6 s off, so the smallest key spacing alone said 120.016 fps (and
// late frames drifted). A rate a BVH's rounded frame time leaves a little off 120 reads as
// 120 with every frame kept, and each frame read is the one written. Needs no shared data (the generated test character).
TEST(GltfWriter, LongClipsKeepTheirRateAndFrames) {
  const std::string path = testing::TempPath("rate_character.gltf");
  testing::WriteTestCharacter(path, 30.0);
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Read(path, &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  for (double rate : {120.0, 120.0005, 1.0 / 0.0083333, 30.0}) {  // The third: CMU's BVH frame time.
    Motion motion;
    motion.frame_rate = rate;
    for (int f = 0; f < 2752; ++f) {
      Pose pose = c.rest_pose;
      pose.rotations[1] = pose.rotations[1] * ExpMap(Eigen::Vector3d(0.3 * std::sin(0.01 * f), 0.0, 0.0));
      motion.frames.push_back(pose);
    }
    std::string glb;
    ASSERT_TRUE(SerializeGltfWithAnimation(doc, c, motion, "take", true, &glb).ok());
    GltfDocument back;
    ASSERT_TRUE(GltfDocument::Parse(glb, "rate.glb", "", &back).ok());
    GltfCharacter bc;
    ASSERT_TRUE(ReadGltfCharacter(back, {}, &bc).ok());
    Motion read;
    ASSERT_TRUE(ReadGltfAnimation(back, bc, {}, &read).ok());
    EXPECT_EQ(read.frame_rate, std::round(rate)) << rate;
    ASSERT_EQ(read.num_frames(), motion.num_frames()) << rate;
    // Each frame read back is the frame written, not a blend of two keys: the keys are
    // written at the rate the reader samples (NominalFrameRate).
    double worst = 0.0;
    for (int f = 0; f < motion.num_frames(); ++f) {
      worst = std::max(worst, read.frames[f].rotations[1].angularDistance(motion.frames[f].rotations[1]));
    }
    EXPECT_LT(worst, 1e-6) << rate;
  }
}

// A .glb file is written with its keys straight from the model (WriteGltfWithAnimation:
// not through tinygltf's copy and the bytes in memory) and holds the bytes
// SerializeGltfWithAnimation makes, whole or animation only, from a Motion or compact.
TEST(GltfWriter, GlbFileHoldsTheSerializedBytes) {
  const std::string path = testing::TempPath("bytes_character.gltf");
  testing::WriteTestCharacter(path, 30.0);
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Read(path, &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  Motion motion;
  motion.frame_rate = 120.0;
  for (int f = 0; f < 301; ++f) {
    Pose pose = c.rest_pose;
    pose.rotations[1] = pose.rotations[1] * ExpMap(Eigen::Vector3d(0.3 * std::sin(0.01 * f), 0.0, 0.0));
    pose.translations[0] += Eigen::Vector3d(0.001 * f, 0.0, 0.0);
    motion.frames.push_back(pose);
  }
  for (bool animation_only : {false, true}) {
    GltfWriteOptions options;
    options.animation_only = animation_only;
    std::string bytes;
    ASSERT_TRUE(SerializeGltfWithAnimation(doc, c, motion, "take", true, &bytes, options).ok());
    const std::string glb = testing::TempPath("bytes.glb");
    ASSERT_TRUE(WriteGltfWithAnimation(doc, c, motion, "take", glb, options).ok());
    EXPECT_EQ(testing::ReadTextFile(glb), bytes) << animation_only;
    const CompactMotion compact(motion);
    ASSERT_TRUE(SerializeGltfWithAnimation(doc, c, compact, "take", true, &bytes, options).ok());
    ASSERT_TRUE(WriteGltfWithAnimation(doc, c, compact, "take", glb, options).ok());
    EXPECT_EQ(testing::ReadTextFile(glb), bytes) << animation_only;
  }
}

// A .gltf whose buffers and texture are separate files, or data: URIs, becomes one .glb
// with everything inside it (the viewer's pages embed characters so): one buffer without
// a URI, the image in a buffer view with its bytes and MIME type, the same character.
TEST(GltfAsGlb, SeparateFilesAndDataUrisBecomeOneSelfContainedGlb) {
  MOCAPSOLVE_DATA_FILE(path, "gltf/CesiumMan.glb");
  GltfDocument original;
  ASSERT_TRUE(GltfDocument::Read(path, &original).ok());
  GltfCharacter expected;
  ASSERT_TRUE(ReadGltfCharacter(original, {}, &expected).ok());
  ASSERT_EQ(original.model().images.size(), 1u);
  const std::vector<unsigned char> texture = original.model().images[0].image;  // The reader keeps its bytes:
  ASSERT_GT(texture.size(), 8u);
  ASSERT_EQ(texture[0], 0xff);  // a JPEG.
  ASSERT_EQ(texture[1], 0xd8);
  for (const auto layout : {testing::GltfLayout::kSeparateFiles, testing::GltfLayout::kDataUris}) {
    const bool files = layout == testing::GltfLayout::kSeparateFiles;
    const std::string gltf = testing::TempPath(files ? "files/CesiumMan.gltf" : "data/CesiumMan.gltf");
    std::filesystem::create_directories(gltf.substr(0, gltf.rfind('/')));
    testing::WriteGltfVariant(path, gltf, layout);
    ASSERT_EQ(testing::FileExists(gltf.substr(0, gltf.rfind('/')) + "/CesiumMan.bin"), files);
    GltfDocument document;
    Status status = GltfDocument::Read(gltf, &document);
    ASSERT_TRUE(status.ok()) << status.message();
    std::string glb;
    status = SerializeGltfAsGlb(document, &glb);
    ASSERT_TRUE(status.ok()) << status.message();
    ASSERT_EQ(glb.substr(0, 4), "glTF");
    GltfDocument back;
    status = GltfDocument::Parse(glb, "back.glb", "/nonexistent", &back);  // Nothing to find beside it.
    ASSERT_TRUE(status.ok()) << status.message();
    const tinygltf::Model& model = back.model();
    ASSERT_EQ(model.buffers.size(), 1u);
    EXPECT_TRUE(model.buffers[0].uri.empty());
    ASSERT_EQ(model.images.size(), 1u);
    EXPECT_TRUE(model.images[0].uri.empty());
    EXPECT_GE(model.images[0].bufferView, 0);
    EXPECT_EQ(model.images[0].mimeType, "image/jpeg");  // From the bytes (the .gltf states none).
    EXPECT_EQ(model.images[0].image, texture);
    GltfCharacter c;
    status = ReadGltfCharacter(back, {}, &c);
    ASSERT_TRUE(status.ok()) << status.message();
    ASSERT_EQ(c.skeleton.num_joints(), expected.skeleton.num_joints());
    ASSERT_EQ(c.mesh.num_vertices(), expected.mesh.num_vertices());
    EXPECT_EQ(c.triangles, expected.triangles);
    EXPECT_EQ(c.animation_names, expected.animation_names);
    for (int j = 0; j < c.skeleton.num_joints(); ++j) EXPECT_EQ(c.skeleton.name(j), expected.skeleton.name(j));
    // 1e-12: the same float32 vertex data, converted to double alike.
    EXPECT_LT((c.mesh.rest_positions() - expected.mesh.rest_positions()).cwiseAbs().maxCoeff(), 1e-12);
    Motion a, b;
    ASSERT_TRUE(ReadGltfAnimation(original, expected, {}, &a).ok());
    ASSERT_TRUE(ReadGltfAnimation(back, c, {}, &b).ok());
    ExpectSameMotion(a, b, 1.0);
    if (files) {  // A texture file gone: an error naming the image, no bytes.
      ASSERT_TRUE(std::filesystem::remove(gltf.substr(0, gltf.rfind('/')) + "/CesiumMan_image0.jpg"));
      GltfDocument missing;
      ASSERT_TRUE(GltfDocument::Read(gltf, &missing).ok());
      std::string none;
      status = SerializeGltfAsGlb(missing, &none);
      ASSERT_FALSE(status.ok());
      EXPECT_NE(status.message().find("image 0 ('CesiumMan_image0.jpg'): could not be read"), std::string::npos)
          << status.message();
      EXPECT_EQ(status.message().find('\n'), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace mocapsolve
