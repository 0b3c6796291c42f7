// The self round trip (a character's own clip as BVH, retargeted back onto it through
// RunRetarget, as `mocapsolve retarget` runs it) on small generated glTF characters that
// have what game and DCC exports have: a root bone at the floor above the hips with an IK
// foot bone under it (no vertices), an `Armature` node above the skeleton with scale 0.01
// and a Z-up to Y-up rotation (joint translations in cm), another node above with a
// translation and a turn, meshes parented to bones without a skin (rigid parts), no
// normals (computed, area-weighted), a quadruped. Each must come back within 0.1 % of its
// height at every joint and frame (measured: float precision); the figures are printed.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "io/bvh_writer.h"
#include "io/gltf_reader.h"
#include "kinematics/forward_kinematics.h"
#include "problems/retarget/mesh_mapping.h"
#include "problems/retarget/retarget_setup.h"
#include "tasks/retarget_task.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

struct FixtureJoint {
  std::string name;
  int parent;              // -1: a skeleton root.
  Eigen::Vector3d offset;  // Metres, Y up (before the variant's nodes above).
  bool has_vertices = true;
};

struct Variant {
  std::string name;
  bool quadruped = false;
  bool floor_root_bone = false;  // Root at the floor above the hips, FootIK.L under it.
  bool armature = false;         // Armature: scale 0.01, Z up -> Y up; joints in cm, Z up.
  bool moved_node = false;       // A node above: translation (1, 0, -2), 30 degrees about y.
  bool rigid_parts = false;      // Unskinned meshes under Head / the last joint.
  bool normals = false;          // NORMAL attributes (else the reader computes them).
};

std::vector<FixtureJoint> Joints(const Variant& v) {
  std::vector<FixtureJoint> j;
  auto add = [&](const std::string& name, const std::string& parent, double x, double y, double z, bool has = true) {
    int p = -1;
    for (size_t k = 0; k < j.size(); ++k) {
      if (j[k].name == parent) p = static_cast<int>(k);
    }
    j.push_back({name, p, Eigen::Vector3d(x, y, z), has});
  };
  if (v.floor_root_bone) add("Root", "", 0, 0, 0, false);
  if (v.quadruped) {
    add("Hips", v.floor_root_bone ? "Root" : "", 0, 0.6, -0.4);
    add("Spine", "Hips", 0, 0.02, 0.3), add("Chest", "Spine", 0, 0, 0.35), add("Neck", "Chest", 0, 0.15, 0.15);
    add("Head", "Neck", 0, 0.1, 0.1), add("Tail", "Hips", 0, 0.05, -0.2), add("Tail1", "Tail", 0, -0.05, -0.25);
    for (const char* side : {"L", "R"}) {
      const double x = side[0] == 'L' ? 0.12 : -0.12;
      const std::string s = side;
      add("BackThigh" + s, "Hips", x, -0.05, 0), add("BackShin" + s, "BackThigh" + s, 0, -0.28, -0.05);
      add("BackFoot" + s, "BackShin" + s, 0, -0.25, 0.03);
      add("FrontLeg" + s, "Chest", x, -0.05, 0.05), add("FrontShin" + s, "FrontLeg" + s, 0, -0.28, 0.02);
      add("FrontFoot" + s, "FrontShin" + s, 0, -0.25, 0.02);
    }
  } else {
    add("Hips", v.floor_root_bone ? "Root" : "", 0, 0.95, 0);
    add("Spine", "Hips", 0, 0.15, 0), add("Chest", "Spine", 0, 0.2, 0), add("Neck", "Chest", 0, 0.2, 0);
    add("Head", "Neck", 0, 0.1, 0.02);
    for (const char* side : {"L", "R"}) {
      const double x = side[0] == 'L' ? 1.0 : -1.0;
      const std::string s = std::string(".") + side;
      add("Shoulder" + s, "Chest", 0.05 * x, 0.15, 0), add("UpperArm" + s, "Shoulder" + s, 0.1 * x, 0, 0);
      add("LowerArm" + s, "UpperArm" + s, 0.28 * x, -0.02, 0), add("Hand" + s, "LowerArm" + s, 0.25 * x, 0, 0);
      add("UpperLeg" + s, "Hips", 0.1 * x, -0.05, 0), add("LowerLeg" + s, "UpperLeg" + s, 0, -0.42, 0.01);
      add("Foot" + s, "LowerLeg" + s, 0, -0.43, 0), add("Toes" + s, "Foot" + s, 0, -0.04, 0.12);
    }
  }
  if (v.floor_root_bone) add("FootIK.L", "Root", 0.1, 0.08, 0, false);
  return j;
}

// Appends `data` (4-byte aligned) to buffer 0 as a new view and accessor; returns the accessor.
int AddAccessor(tinygltf::Model* model, const std::vector<float>& data, int type, int count,
                std::vector<double> min = {}, std::vector<double> max = {},
                int component = TINYGLTF_COMPONENT_TYPE_FLOAT, const std::vector<unsigned char>& bytes = {}) {
  std::vector<unsigned char>& buffer = model->buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  const unsigned char* begin = bytes.empty() ? reinterpret_cast<const unsigned char*>(data.data()) : bytes.data();
  const size_t size = bytes.empty() ? data.size() * sizeof(float) : bytes.size();
  buffer.insert(buffer.end(), begin, begin + size);
  while (buffer.size() % 4) buffer.push_back(0);
  view.byteLength = size;
  model->bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(model->bufferViews.size()) - 1;
  accessor.componentType = component;
  accessor.count = count;
  accessor.type = type;
  accessor.minValues = min;
  accessor.maxValues = max;
  model->accessors.push_back(accessor);
  return static_cast<int>(model->accessors.size()) - 1;
}

// A tetrahedron of radius r around `centre` (4 vertices, 4 triangles): positions, normals.
void Tetra(const Eigen::Vector3d& centre, double r, std::vector<float>* positions, std::vector<float>* normals) {
  const Eigen::Vector3d corners[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  for (const Eigen::Vector3d& c : corners) {
    for (int k = 0; k < 3; ++k) positions->push_back(static_cast<float>(centre[k] + r * c[k]));
    for (int k = 0; k < 3; ++k) normals->push_back(static_cast<float>(c.normalized()[k]));
  }
}

tinygltf::Primitive Primitive(tinygltf::Model* model, const std::vector<float>& positions,
                              const std::vector<float>& normals, bool with_normals) {
  const int nv = static_cast<int>(positions.size() / 3);
  std::vector<double> lo(3, 1e30), hi(3, -1e30);
  for (int v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k)
      lo[k] = std::min(lo[k], double(positions[3 * v + k])), hi[k] = std::max(hi[k], double(positions[3 * v + k]));
  }
  std::vector<unsigned char> indices;
  for (int t = 0; t < nv / 4; ++t) {
    const int faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    for (const auto& face : faces) {
      for (int k : face) {
        const uint16_t i = static_cast<uint16_t>(4 * t + k);
        indices.push_back(i & 0xff), indices.push_back(i >> 8);
      }
    }
  }
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] = AddAccessor(model, positions, TINYGLTF_TYPE_VEC3, nv, lo, hi);
  if (with_normals) primitive.attributes["NORMAL"] = AddAccessor(model, normals, TINYGLTF_TYPE_VEC3, nv);
  primitive.indices =
      AddAccessor(model, {}, TINYGLTF_TYPE_SCALAR, 3 * nv, {}, {}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, indices);
  return primitive;
}

// The character and a 12-frame clip (30 fps: smooth random rotations of every joint, the
// hips walking forward and bobbing, the IK foot sliding) as a .gltf.
void WriteFixture(const Variant& v, const std::string& path) {
  const std::vector<FixtureJoint> joints = Joints(v);
  const int n = static_cast<int>(joints.size());
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.buffers.resize(1);
  // Nodes above: [moved] -> [Armature] -> joints. A = their similarity (world from the joints' parent).
  Eigen::Affine3d above = Eigen::Affine3d::Identity();
  std::vector<int> chain;
  if (v.moved_node) {
    tinygltf::Node node;
    node.name = "Scene";
    node.translation = {1, 0, -2};
    const Eigen::Quaterniond q(Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitY()));
    node.rotation = {q.x(), q.y(), q.z(), q.w()};
    above = above * Eigen::Translation3d(1, 0, -2) * q;
    model.nodes.push_back(node), chain.push_back(static_cast<int>(model.nodes.size()) - 1);
  }
  const Eigen::Quaterniond z_up(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()));
  if (v.armature) {
    tinygltf::Node node;
    node.name = "Armature";
    node.rotation = {z_up.x(), z_up.y(), z_up.z(), z_up.w()};
    node.scale = {0.01, 0.01, 0.01};
    above = above * z_up * Eigen::Scaling(0.01);
    model.nodes.push_back(node), chain.push_back(static_cast<int>(model.nodes.size()) - 1);
  }
  const int first_joint_node = static_cast<int>(model.nodes.size());
  const double unit = v.armature ? 100.0 : 1.0;
  std::vector<Eigen::Vector3d> local(n), world(n);  // Joint translations in their nodes; rest world (Y up, m).
  for (int j = 0; j < n; ++j) {
    local[j] = v.armature ? Eigen::Vector3d(unit * (z_up.conjugate() * joints[j].offset)) : joints[j].offset;
    world[j] = (joints[j].parent >= 0 ? world[joints[j].parent] : Eigen::Vector3d::Zero()) + joints[j].offset;
    tinygltf::Node node;
    node.name = joints[j].name;
    node.translation = {local[j].x(), local[j].y(), local[j].z()};
    model.nodes.push_back(node);
    if (joints[j].parent >= 0)
      model.nodes[first_joint_node + joints[j].parent].children.push_back(first_joint_node + j);
  }
  for (size_t k = 0; k + 1 < chain.size(); ++k) model.nodes[chain[k]].children.push_back(chain[k + 1]);
  std::vector<int> roots;
  for (int j = 0; j < n; ++j) {
    if (joints[j].parent < 0) roots.push_back(first_joint_node + j);
  }
  if (!chain.empty()) {
    for (int r : roots) model.nodes[chain.back()].children.push_back(r);
    roots = {chain.front()};
  }
  // The skinned mesh: a tetrahedron at each joint with vertices, in the world of the rest pose
  // (bind space = world: IBM_j = (A * T(world_j in the joints' parent frame))^-1).
  std::vector<float> positions, normals, weights, ibms;
  std::vector<unsigned char> joint_bytes;
  const Eigen::Affine3d inverse_above = above.inverse();
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector3d in_parent =
        inverse_above * (above * (unit * (v.armature ? Eigen::Vector3d(z_up.conjugate() * world[j]) : world[j])));
    const Eigen::Matrix4d ibm = (above * Eigen::Translation3d(in_parent)).matrix().inverse();
    for (int k = 0; k < 16; ++k) ibms.push_back(static_cast<float>(ibm(k % 4, k / 4)));
    if (!joints[j].has_vertices || (v.rigid_parts && joints[j].name == "Head")) continue;
    Tetra(above * (unit * (v.armature ? Eigen::Vector3d(z_up.conjugate() * world[j]) : world[j])), 0.03, &positions,
          &normals);
    for (int c = 0; c < 4; ++c) {
      joint_bytes.insert(joint_bytes.end(), {static_cast<unsigned char>(j), 0, 0, 0});
      weights.insert(weights.end(), {1, 0, 0, 0});
    }
  }
  tinygltf::Primitive body = Primitive(&model, positions, normals, v.normals);
  const int nv = static_cast<int>(positions.size() / 3);
  body.attributes["WEIGHTS_0"] = AddAccessor(&model, weights, TINYGLTF_TYPE_VEC4, nv);
  body.attributes["JOINTS_0"] =
      AddAccessor(&model, {}, TINYGLTF_TYPE_VEC4, nv, {}, {}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, joint_bytes);
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(body);
  model.meshes.push_back(mesh);
  tinygltf::Skin skin;
  for (int j = 0; j < n; ++j) skin.joints.push_back(first_joint_node + j);
  skin.inverseBindMatrices = AddAccessor(&model, ibms, TINYGLTF_TYPE_MAT4, n);
  model.skins.push_back(skin);
  tinygltf::Node body_node;
  body_node.name = "Body";
  body_node.mesh = 0;
  body_node.skin = 0;
  model.nodes.push_back(body_node);
  roots.push_back(static_cast<int>(model.nodes.size()) - 1);
  if (v.rigid_parts) {  // A helmet on the head, in the head's frame (no skin: weight 1 on the bone).
    std::vector<float> p, q;
    Tetra(Eigen::Vector3d(0, 0.1 * unit, 0), 0.06 * unit, &p, &q);
    tinygltf::Mesh helmet;
    helmet.primitives.push_back(Primitive(&model, p, q, v.normals));
    model.meshes.push_back(helmet);
    tinygltf::Node node;
    node.name = "Helmet";
    node.mesh = static_cast<int>(model.meshes.size()) - 1;
    model.nodes.push_back(node);
    for (int j = 0; j < n; ++j) {
      if (joints[j].name == "Head")
        model.nodes[first_joint_node + j].children.push_back(static_cast<int>(model.nodes.size()) - 1);
    }
  }
  // The clip.
  const int frames = 12;
  std::vector<float> times;
  for (int f = 0; f < frames; ++f) times.push_back(static_cast<float>(f / 30.0));
  tinygltf::Animation animation;
  animation.name = "Clip";
  auto channel = [&](int node, const std::string& path_name, const std::vector<float>& values, int type) {
    tinygltf::AnimationSampler sampler;
    sampler.input = AddAccessor(&model, times, TINYGLTF_TYPE_SCALAR, frames, {0.0}, {double(times.back())});
    sampler.output = AddAccessor(&model, values, type, frames);
    sampler.interpolation = "LINEAR";
    animation.samplers.push_back(sampler);
    tinygltf::AnimationChannel c;
    c.sampler = static_cast<int>(animation.samplers.size()) - 1;
    c.target_node = node;
    c.target_path = path_name;
    animation.channels.push_back(c);
  };
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int j = 0; j < n; ++j) {
    // The root bone turns about the vertical only and the hips tilt little (a clip in which
    // the body stays upright on average: the source's up axis comes from the motion).
    const double scale = joints[j].name == "Root" || joints[j].name == "Hips" ? 0.15 : 0.5;
    Eigen::Vector3d amplitude(scale * uniform(rng), scale * uniform(rng), scale * uniform(rng));
    if (joints[j].name == "Root") amplitude = (v.armature ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY()) * 0.5;
    const double phase = 3.0 * uniform(rng);
    std::vector<float> rotations, translations;
    for (int f = 0; f < frames; ++f) {
      const Eigen::Vector3d a = amplitude * std::sin(6.0 * f / 30.0 + phase);
      const Eigen::Quaterniond q(Eigen::AngleAxisd(a.norm(), a.norm() > 0 ? a.normalized() : Eigen::Vector3d::UnitX()));
      rotations.insert(rotations.end(), {float(q.x()), float(q.y()), float(q.z()), float(q.w())});
      Eigen::Vector3d t = local[j];
      if (joints[j].name == "Hips")
        t += (v.armature ? unit : 1.0) * Eigen::Vector3d(0.01 * f, 0.02 * std::sin(f), v.armature ? 0.0 : 0.04 * f);
      if (joints[j].name == "FootIK.L") t += Eigen::Vector3d(0, 0, 0.03 * f);
      translations.insert(translations.end(), {float(t.x()), float(t.y()), float(t.z())});
    }
    channel(first_joint_node + j, "rotation", rotations, TINYGLTF_TYPE_VEC4);
    if (joints[j].name == "Hips" || joints[j].name == "FootIK.L")
      channel(first_joint_node + j, "translation", translations, TINYGLTF_TYPE_VEC3);
  }
  model.animations.push_back(animation);
  tinygltf::Scene scene;
  scene.nodes = roots;
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&model, path, true, true, true, false)) << path;
}

class FixtureRoundTripTest : public ::testing::TestWithParam<Variant> {};

TEST_P(FixtureRoundTripTest, JointsWithinOneThousandthOfTheHeight) {
  const Variant& v = GetParam();
  const std::string path = testing::TempPath(v.name + ".gltf");
  WriteFixture(v, path);
  if (HasFatalFailure()) return;
  GltfDocument document;
  Status status = GltfDocument::Read(path, &document);
  ASSERT_TRUE(status.ok()) << status.message();
  GltfCharacter character;
  status = ReadGltfCharacter(document, GltfReadOptions(), &character);
  ASSERT_TRUE(status.ok()) << status.message();
  Motion clip;
  ASSERT_TRUE(ReadGltfAnimation(document, character, GltfAnimationOptions(), &clip).ok());
  const std::string bvh = testing::TempPath(v.name + ".bvh");
  ASSERT_TRUE(WriteBvh(bvh, character.skeleton, clip).ok());
  Eigen::Matrix3Xd rest;
  const Pose bind = character.bind_pose.rotations.empty() ? RestPose(character.skeleton) : character.bind_pose;
  BindPoseMesh(character.mesh, WorldFromBindRotation(character.skeleton, bind, character.rest_pose), &rest, nullptr);
  const double height = ComputeCharacterFrame(rest).height;
  ASSERT_GT(height, 0.0);
  RetargetInputs inputs;
  inputs.source = bvh;
  inputs.target = path;
  RetargetTaskResult task;
  status = RunRetarget(inputs, RetargetConfig(), nullptr, &task);
  ASSERT_TRUE(status.ok()) << v.name << ": " << status.message();
  const std::vector<Vector3dVector> truth = ClipJointPositions(character.skeleton, clip);
  const std::vector<Vector3dVector> got = ClipJointPositions(character.skeleton, task.retarget.clip.motion);
  ASSERT_EQ(got.size(), truth.size());
  double worst = 0.0;
  for (size_t f = 0; f < truth.size(); ++f) {
    for (int j = 0; j < character.skeleton.num_joints(); ++j)
      worst = std::max(worst, (truth[f][j] - got[f][j]).norm() / height);
  }
  std::printf("fixture self round trip %-16s %2d joints: max joint error %.6f %% of height %.4g\n", v.name.c_str(),
              character.skeleton.num_joints(), 100.0 * worst, height);
  for (const std::string& note : task.retarget.notes) std::printf("  note: %s\n", note.c_str());
  EXPECT_TRUE(task.retarget.own_skeleton) << v.name;
  EXPECT_LE(worst, 1e-3) << v.name;
}

INSTANTIATE_TEST_SUITE_P(GameAndDccExports, FixtureRoundTripTest,
                         ::testing::Values(Variant{"plain"}, Variant{"floor_root_bone", false, true},
                                           Variant{"armature_cm", false, false, true},
                                           Variant{"moved_node", false, false, false, true},
                                           Variant{"rigid_parts", false, false, false, false, true},
                                           Variant{"with_normals", false, false, false, false, false, true},
                                           Variant{"game_rig", false, true, true, true, true},
                                           Variant{"quadruped", true},
                                           Variant{"quadruped_rig", true, true, true, true, true}),
                         [](const ::testing::TestParamInfo<Variant>& info) { return info.param.name; });

}  // namespace
}  // namespace mocapsolve
