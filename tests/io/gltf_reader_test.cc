#include "io/gltf_reader.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "io/atomic_file.h"
#include "io/gltf_writer.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/skinning.h"
#include "tests/gltf_test_files.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// ---------------------------------------------------------------------------------
// An independent glTF evaluator for the tests: full 4x4 node matrices (scales as they
// are), LINEAR/STEP samplers on float accessors, and glTF's skinning formula
// v = sum_b w_b (G_b IBM_b) v0. It shares no code with the reader.

std::vector<float> Floats(const tinygltf::Model& m, int accessor) {
  const tinygltf::Accessor& a = m.accessors[accessor];
  const tinygltf::BufferView& view = m.bufferViews[a.bufferView];
  const int n = tinygltf::GetNumComponentsInType(a.type);
  const int stride = a.ByteStride(view);
  std::vector<float> out(a.count * n);
  const unsigned char* base = m.buffers[view.buffer].data.data() + view.byteOffset + a.byteOffset;
  for (size_t e = 0; e < a.count; ++e) {
    for (int c = 0; c < n; ++c) {
      if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        std::memcpy(&out[e * n + c], base + e * stride + 4 * c, 4);
      } else if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
        out[e * n + c] = base[e * stride + c] / (a.normalized ? 255.f : 1.f);
      } else {
        uint16_t u;
        std::memcpy(&u, base + e * stride + 2 * c, 2);
        out[e * n + c] = u / (a.normalized ? 65535.f : 1.f);
      }
    }
  }
  return out;
}

struct NodeTrs {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Quaterniond r = Eigen::Quaterniond::Identity();
  Eigen::Vector3d s = Eigen::Vector3d::Ones();
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
  bool has_matrix = false;
};

std::vector<NodeTrs> DefaultTrs(const tinygltf::Model& m) {
  std::vector<NodeTrs> out(m.nodes.size());
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const tinygltf::Node& n = m.nodes[i];
    if (n.translation.size() == 3) out[i].t = Eigen::Vector3d(n.translation[0], n.translation[1], n.translation[2]);
    if (n.rotation.size() == 4) out[i].r = Eigen::Quaterniond(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    if (n.scale.size() == 3) out[i].s = Eigen::Vector3d(n.scale[0], n.scale[1], n.scale[2]);
    if (n.matrix.size() == 16) {
      out[i].has_matrix = true;
      for (int k = 0; k < 16; ++k) out[i].matrix(k % 4, k / 4) = n.matrix[k];
    }
  }
  return out;
}

// Node TRS at time t of animation `anim` (LINEAR with slerp, STEP; clamped ends).
std::vector<NodeTrs> AnimatedTrs(const tinygltf::Model& m, int anim, double t) {
  std::vector<NodeTrs> trs = DefaultTrs(m);
  const tinygltf::Animation& a = m.animations[anim];
  for (const tinygltf::AnimationChannel& ch : a.channels) {
    const tinygltf::AnimationSampler& s = a.samplers[ch.sampler];
    const std::vector<float> times = Floats(m, s.input);
    const std::vector<float> values = Floats(m, s.output);
    const int n = ch.target_path == "rotation" ? 4 : 3;
    if (ch.target_path == "weights") continue;
    size_t k0 = 0, k1 = 0;
    double u = 0.0;
    if (t <= times.front()) {
      k0 = k1 = 0;
    } else if (t >= times.back()) {
      k0 = k1 = times.size() - 1;
    } else {
      while (times[k1] <= t) ++k1;
      k0 = k1 - 1;
      u = (t - times[k0]) / (times[k1] - times[k0]);
    }
    if (s.interpolation == "STEP") u = 0.0;
    const float* a0 = &values[k0 * n];
    const float* a1 = &values[k1 * n];
    if (n == 4) {
      Eigen::Quaterniond q0(a0[3], a0[0], a0[1], a0[2]), q1(a1[3], a1[0], a1[1], a1[2]);
      trs[ch.target_node].r = q0.normalized().slerp(u, q1.normalized());
    } else {
      Eigen::Vector3d v0(a0[0], a0[1], a0[2]), v1(a1[0], a1[1], a1[2]);
      Eigen::Vector3d v = (1 - u) * v0 + u * v1;
      (ch.target_path == "translation" ? trs[ch.target_node].t : trs[ch.target_node].s) = v;
    }
  }
  return trs;
}

std::vector<Eigen::Matrix4d> WorldMatrices(const tinygltf::Model& m, const std::vector<NodeTrs>& trs) {
  std::vector<int> parent(m.nodes.size(), -1);
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    for (int c : m.nodes[i].children) parent[c] = static_cast<int>(i);
  }
  std::vector<Eigen::Matrix4d> world(m.nodes.size());
  std::vector<bool> done(m.nodes.size(), false);
  std::function<void(int)> visit = [&](int i) {
    if (done[i]) return;
    Eigen::Matrix4d local = Eigen::Matrix4d::Identity();
    if (trs[i].has_matrix) {
      local = trs[i].matrix;
    } else {
      Eigen::Affine3d a = Eigen::Translation3d(trs[i].t) * trs[i].r.normalized() * Eigen::Scaling(trs[i].s);
      local = a.matrix();
    }
    if (parent[i] >= 0) {
      visit(parent[i]);
      world[i] = world[parent[i]] * local;
    } else {
      world[i] = local;
    }
    done[i] = true;
  };
  for (size_t i = 0; i < m.nodes.size(); ++i) visit(static_cast<int>(i));
  return world;
}

// Vertex count of the first primitive of the first mesh using skin `skin` (the first
// vertices of the reader's merged mesh).
int FirstPrimitiveVertexCount(const tinygltf::Model& m, int skin) {
  for (const tinygltf::Node& n : m.nodes) {
    if (n.skin == skin && n.mesh >= 0) {
      return static_cast<int>(m.accessors[m.meshes[n.mesh].primitives[0].attributes.at("POSITION")].count);
    }
  }
  return 0;
}

// glTF skinning of vertex v of the first primitive of the first mesh using skin `skin`.
Eigen::Vector3d GltfSkinnedVertex(const tinygltf::Model& m, int skin, const std::vector<Eigen::Matrix4d>& world,
                                  int v) {
  int mesh = -1;
  for (const tinygltf::Node& n : m.nodes) {
    if (n.skin == skin && n.mesh >= 0) {
      mesh = n.mesh;
      break;
    }
  }
  const tinygltf::Primitive& p = m.meshes[mesh].primitives[0];
  const std::vector<float> pos = Floats(m, p.attributes.at("POSITION"));
  const std::vector<float> joints = Floats(m, p.attributes.at("JOINTS_0"));
  const std::vector<float> weights = Floats(m, p.attributes.at("WEIGHTS_0"));
  const tinygltf::Skin& s = m.skins[skin];
  const std::vector<float> ibm = Floats(m, s.inverseBindMatrices);
  Eigen::Vector4d v0(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1.0);
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  double total = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double w = weights[4 * v + k];
    if (w == 0.0) continue;
    const int j = static_cast<int>(joints[4 * v + k]);
    Eigen::Matrix4d inv_bind;
    for (int e = 0; e < 16; ++e) inv_bind(e % 4, e / 4) = ibm[16 * j + e];
    sum += w * (world[s.joints[j]] * inv_bind * v0);
    total += w;
  }
  return sum.head<3>() / total;
}

// Largest extent of the mesh skinned at a pose (glTF world units).
double Extent(const GltfCharacter& c, const Pose& pose) {
  FkData fk(c.skeleton);
  ForwardKinematics(c.skeleton, pose, &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(c.mesh, fk, &transforms);
  Eigen::Matrix3Xd p;
  SkinMesh(c.mesh, transforms, &p, nullptr);
  return (p.rowwise().maxCoeff() - p.rowwise().minCoeff()).maxCoeff();
}

// Y (glTF's up) extent of the mesh skinned at a pose.
double YExtent(const GltfCharacter& c, const Pose& pose) {
  FkData fk(c.skeleton);
  ForwardKinematics(c.skeleton, pose, &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(c.mesh, fk, &transforms);
  Eigen::Matrix3Xd p;
  SkinMesh(c.mesh, transforms, &p, nullptr);
  return p.row(1).maxCoeff() - p.row(1).minCoeff();
}

struct CharacterCase {
  const char* file;
  int joints;  // Per shared/data/README.md (skin 0).
};

class GltfCharacters : public ::testing::TestWithParam<CharacterCase> {};

TEST_P(GltfCharacters, LoadsWithJointCountAndSkinningMatchesGltf) {
  MOCAPSOLVE_DATA_FILE(path, std::string("gltf/") + GetParam().file);
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Read(path, &doc).ok());
  GltfCharacter c;
  const Status status = ReadGltfCharacter(doc, {}, &c);
  ASSERT_TRUE(status.ok()) << status.message();
  // The skin's joints, plus one root when several joints have no joint parent.
  const int skin_joints = static_cast<int>(c.skin_joints.size());
  EXPECT_EQ(skin_joints, GetParam().joints);
  EXPECT_GE(c.skeleton.num_joints(), skin_joints);
  EXPECT_LE(c.skeleton.num_joints(), skin_joints + 1);
  EXPECT_GT(c.mesh.num_vertices(), 0);
  EXPECT_GT(c.triangles.cols(), 0);
  EXPECT_LT(c.triangles.maxCoeff(), c.mesh.num_vertices());
  EXPECT_EQ(c.skeleton.unit().name, "m");
  const double height = Extent(c, c.rest_pose);
  std::printf("%s: %d joints (skin %d), %d vertices, %d triangles, rest-pose extent %.4f m, height (y) "
              "rest pose %.4f m, bind pose %.4f m, bind scale %g, %zu animations, %zu warnings\n",
              GetParam().file, c.skeleton.num_joints(), skin_joints, c.mesh.num_vertices(),
              static_cast<int>(c.triangles.cols()), height, YExtent(c, c.rest_pose), YExtent(c, c.bind_pose),
              c.bind_scale, c.animation_names.size(), c.warnings.size());
  for (const std::string& w : c.warnings) std::printf("  warning: %s\n", w.c_str());

  // FK of the bind pose places each skin joint at its inverse bind matrix (scale removed).
  FkData fk(c.skeleton);
  ForwardKinematics(c.skeleton, c.bind_pose, &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(c.mesh, fk, &transforms);
  for (const Eigen::Isometry3d& s : transforms) {
    // 1e-9 (relative to the height): the bind pose is built from these transforms.
    EXPECT_LT((s.matrix() - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff(), 1e-9 * (1 + height * c.bind_scale));
  }

  // Every animation: finite unit quaternions; and glTF's own skinning of some vertices
  // at some frames equals FK + SkinPosition (scaled by bind_scale).
  const tinygltf::Model& m = doc.model();
  for (size_t a = 0; a < c.animation_names.size(); ++a) {
    Motion motion;
    GltfAnimationOptions options;
    options.animation = std::to_string(a);
    std::vector<std::string> warnings;
    const Status s = ReadGltfAnimation(doc, c, options, &motion, &warnings);
    ASSERT_TRUE(s.ok()) << s.message();
    ASSERT_GT(motion.num_frames(), 0);
    EXPECT_TRUE(ValidateMotion(c.skeleton, motion).ok());
    for (const std::string& w : warnings) std::printf("  animation %zu: %s\n", a, w.c_str());
    double t0 = 1e300;
    for (const tinygltf::AnimationChannel& ch : m.animations[a].channels) {
      t0 = std::min<double>(t0, Floats(m, m.animations[a].samplers[ch.sampler].input).front());
    }
    for (int f : {0, motion.num_frames() / 3, motion.num_frames() - 1}) {
      ForwardKinematics(c.skeleton, motion.frames[f], &fk);
      ComputeSkinningTransforms(c.mesh, fk, &transforms);
      const std::vector<Eigen::Matrix4d> world =
          WorldMatrices(m, AnimatedTrs(m, static_cast<int>(a), t0 + f / motion.frame_rate));
      const int nv = FirstPrimitiveVertexCount(m, c.skin);
      ASSERT_GT(nv, 0);
      for (int v = 0; v < nv; v += std::max(1, nv / 25)) {
        const Eigen::Vector3d ours = SkinPosition(c.mesh, transforms, v);
        const Eigen::Vector3d theirs = GltfSkinnedVertex(m, c.skin, world, v);
        // 1e-5 of the height: float data, double arithmetic on both sides.
        ASSERT_LT((ours - theirs).norm(), 1e-5 * height)
            << GetParam().file << " animation " << a << " frame " << f << " vertex " << v;
      }
      // Our FK equals glTF's node world positions for the skin joints.
      for (size_t k = 0; k < c.skin_joints.size(); ++k) {
        const Eigen::Vector3d p = world[m.skins[c.skin].joints[k]].topRightCorner<3, 1>();
        // 1e-6 of the height: float node scales that are uniform only to ~1e-7 are
        // baked as uniform; 1e-5 where the reader warned of a non-uniform scale
        // (RobotExpressive's legs: 1 - 1e-5).
        const double tolerance = (c.warnings.empty() ? 1e-6 : 1e-5) * height;
        ASSERT_LT((fk.world_positions[c.skin_joints[k]] - p).norm(), tolerance)
            << GetParam().file << " joint " << k;
      }
    }
  }
}

// RobotExpressive binds its right hand to skin 0 and its left hand to skin 1 (the same 43
// joints, its own inverse bind matrices): both hands are read, the left one weighted to the
// left arm's joints and lying as the mirror image of the right one (the robot is symmetric
// about x = 0 in its bind pose), each 554 vertices.
TEST(GltfOtherSkins, RobotExpressiveLeftHandFromItsSecondSkin) {
  MOCAPSOLVE_DATA_FILE(path, "gltf/RobotExpressive.glb");
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(path, {}, &c).ok());
  ASSERT_GT(c.mesh.num_vertices(), 2 * 554);
  const Eigen::Matrix3Xd& rest = c.mesh.rest_positions();  // The bind pose.
  Eigen::Vector3d right = Eigen::Vector3d::Zero(), left = Eigen::Vector3d::Zero();
  for (int v = 0; v < 554; ++v) {
    right += rest.col(v) / 554.0;
    left += rest.col(554 + v) / 554.0;
    for (int k = c.mesh.weight_begin(554 + v); k < c.mesh.weight_end(554 + v); ++k) {
      const std::string& name = c.skeleton.name(c.mesh.weight_joint(k));
      ASSERT_EQ(name.substr(name.size() - 2), ".L") << "vertex " << 554 + v;
    }
  }
  const double height = rest.row(1).maxCoeff() - rest.row(1).minCoeff();
  EXPECT_GT(std::abs(right.x()), 0.1 * height);
  EXPECT_LT((Eigen::Vector3d(-left.x(), left.y(), left.z()) - right).norm(), 0.01 * height)
      << "right hand " << right.transpose() << ", left " << left.transpose();
}

// RobotExpressive skins only its hands; its head, torso, arms and legs are mesh nodes
// parented to bones. They are rigid parts of the character's mesh (weight 1 on the bone):
// animated, each vertex is where glTF's node transforms put it.
TEST(GltfRigidParts, RobotExpressiveBodyMovesWithItsBones) {
  MOCAPSOLVE_DATA_FILE(path, "gltf/RobotExpressive.glb");
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Read(path, &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  const tinygltf::Model& m = doc.model();
  std::vector<int> joint_node(m.nodes.size(), 0), parent(m.nodes.size(), -1);
  for (int n : m.skins[c.skin].joints) joint_node[n] = 1;
  for (size_t n = 0; n < m.nodes.size(); ++n) {
    for (int child : m.nodes[n].children) parent[child] = static_cast<int>(n);
  }
  std::vector<std::pair<int, Eigen::Vector3d>> rigid;  // (node, vertex in the node's frame), in file order.
  for (size_t n = 0; n < m.nodes.size(); ++n) {
    if (m.nodes[n].skin >= 0 || m.nodes[n].mesh < 0) continue;
    bool under_joint = false;
    for (int p = parent[n]; p >= 0 && !under_joint; p = parent[p]) under_joint = joint_node[p] == 1;
    if (!under_joint) continue;
    for (const tinygltf::Primitive& prim : m.meshes[m.nodes[n].mesh].primitives) {
      const std::vector<float> v = Floats(m, prim.attributes.at("POSITION"));
      for (size_t k = 0; k + 2 < v.size(); k += 3) rigid.emplace_back(static_cast<int>(n), Eigen::Vector3d(v[k], v[k + 1], v[k + 2]));
    }
  }
  ASSERT_GT(rigid.size(), 1000u);
  const int first = c.mesh.num_vertices() - static_cast<int>(rigid.size());
  ASSERT_GT(first, 0);  // The skinned hands come first.
  double height = 0.0;
  FkData fk(c.skeleton);
  ForwardKinematics(c.skeleton, c.rest_pose, &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(c.mesh, fk, &transforms);
  Eigen::Matrix3Xd rest;
  SkinMesh(c.mesh, transforms, &rest, nullptr);
  height = rest.row(1).maxCoeff() - rest.row(1).minCoeff();
  EXPECT_GT(height, 3.0);  // The robot's body (the hands alone span less than a metre).
  Motion motion;
  ASSERT_TRUE(ReadGltfAnimation(doc, c, GltfAnimationOptions(), &motion).ok());
  double t0 = 1e300;
  for (const tinygltf::AnimationChannel& ch : m.animations[0].channels) {
    t0 = std::min<double>(t0, Floats(m, m.animations[0].samplers[ch.sampler].input).front());
  }
  for (int f : {0, motion.num_frames() / 2}) {
    ForwardKinematics(c.skeleton, motion.frames[f], &fk);
    ComputeSkinningTransforms(c.mesh, fk, &transforms);
    const std::vector<Eigen::Matrix4d> world = WorldMatrices(m, AnimatedTrs(m, 0, t0 + f / motion.frame_rate));
    for (size_t k = 0; k < rigid.size(); k += 37) {
      const Eigen::Vector3d theirs = (world[rigid[k].first] * rigid[k].second.homogeneous()).head<3>();
      const Eigen::Vector3d ours = SkinPosition(c.mesh, transforms, first + static_cast<int>(k));
      // 1e-4 of the height: the legs' scales, uniform to 1e-5, are baked as uniform.
      ASSERT_LT((ours - theirs).norm(), 1e-4 * height) << "frame " << f << " rigid vertex " << k;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    SharedData, GltfCharacters,
    ::testing::Values(CharacterCase{"Xbot.glb", 65}, CharacterCase{"Ely.glb", 67},
                      CharacterCase{"Soldier.glb", 49}, CharacterCase{"CesiumMan.glb", 19},
                      CharacterCase{"RiggedFigure.glb", 19}, CharacterCase{"RobotExpressive.glb", 43},
                      CharacterCase{"Fox.glb", 24}),
    [](const ::testing::TestParamInfo<CharacterCase>& info) {
      std::string name = info.param.file;
      return name.substr(0, name.find('.'));
    });


// ---------------------------------------------------------------------------------
// A small glTF built here: every sampler kind, a baked non-joint node between joints,
// uniform scales, a scale channel, u8/u16 joints, normalized u16 and float weights, a
// sparse accessor, two extra skins with several root joints.
namespace tiny {

std::string Base64(const std::string& in) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(in[i]) << 16) |
                       (static_cast<unsigned char>(in[i + 1]) << 8) | static_cast<unsigned char>(in[i + 2]);
    for (int k = 3; k >= 0; --k) out += table[(v >> (6 * k)) & 63];
  }
  if (i + 1 == in.size()) {
    const unsigned v = static_cast<unsigned char>(in[i]) << 16;
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == in.size()) {
    const unsigned v = (static_cast<unsigned char>(in[i]) << 16) | (static_cast<unsigned char>(in[i + 1]) << 8);
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += table[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

struct Builder {
  std::string bin;
  std::vector<std::string> views, accessors;

  int View(const void* data, size_t bytes) {
    while (bin.size() % 4) bin.push_back('\0');
    views.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(bin.size()) +
                    ",\"byteLength\":" + std::to_string(bytes) + "}");
    bin.append(static_cast<const char*>(data), bytes);
    return static_cast<int>(views.size()) - 1;
  }
  template <typename T>
  int Add(const std::vector<T>& v, int component_type, const std::string& type, int n,
          const std::string& extra = "") {
    const int view = View(v.data(), v.size() * sizeof(T));
    accessors.push_back("{\"bufferView\":" + std::to_string(view) + ",\"componentType\":" +
                        std::to_string(component_type) + ",\"count\":" + std::to_string(v.size() / n) +
                        ",\"type\":\"" + type + "\"" + extra + "}");
    return static_cast<int>(accessors.size()) - 1;
  }
  int Floats(const std::vector<float>& v, const std::string& type, int n) { return Add(v, 5126, type, n); }
  int Times(const std::vector<float>& v) {
    char mm[96];
    std::snprintf(mm, sizeof mm, ",\"min\":[%.9g],\"max\":[%.9g]", v.front(), v.back());
    return Add(v, 5126, "SCALAR", 1, mm);
  }
  std::string Json(const std::string& body) const {
    std::string out = "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":" +
                      std::to_string(bin.size()) + ",\"uri\":\"data:application/octet-stream;base64," +
                      Base64(bin) + "\"}],\"bufferViews\":[";
    for (size_t i = 0; i < views.size(); ++i) out += (i ? "," : "") + views[i];
    out += "],\"accessors\":[";
    for (size_t i = 0; i < accessors.size(); ++i) out += (i ? "," : "") + accessors[i];
    return out + "]," + body + "}";
  }
};

Eigen::Quaterniond Q(double deg, const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(deg * M_PI / 180.0, axis.normalized()));
}
std::string Vec(const Eigen::Quaterniond& q) {
  char s[128];
  std::snprintf(s, sizeof s, "[%.17g,%.17g,%.17g,%.17g]", q.x(), q.y(), q.z(), q.w());
  return s;
}

// Node defaults (TRS); node 5 holds the mesh, node 6 is a separate top-level node.
struct Scene {
  std::vector<NodeTrs> trs;
  Scene() : trs(7) {
    trs[0].s = Eigen::Vector3d::Constant(0.01);
    trs[0].r = Q(90, Eigen::Vector3d::UnitX());
    trs[1].t = Eigen::Vector3d(0, 0, 100);
    trs[2].t = Eigen::Vector3d(10, 0, 0);
    trs[2].r = Q(30, Eigen::Vector3d::UnitZ());
    trs[3].t = Eigen::Vector3d(0, -50, 0);
    trs[3].r = Q(10, Eigen::Vector3d(1, 1, 0));
    trs[4].t = Eigen::Vector3d(0, 30, 0);
    trs[4].s = Eigen::Vector3d::Constant(2.0);
    trs[6].t = Eigen::Vector3d(5, 5, 5);
  }
};

std::vector<Eigen::Matrix4d> Worlds(const std::vector<NodeTrs>& trs) {
  std::vector<int> parent = {-1, 0, 1, 2, 1, -1, -1};
  std::vector<Eigen::Matrix4d> world(trs.size());
  for (size_t i = 0; i < trs.size(); ++i) {
    const Eigen::Affine3d local = Eigen::Translation3d(trs[i].t) * trs[i].r * Eigen::Scaling(trs[i].s);
    world[i] = parent[i] < 0 ? local.matrix() : Eigen::Matrix4d(world[parent[i]] * local.matrix());
  }
  return world;
}

// The leg's CUBICSPLINE keys (in-tangent, value, out-tangent per key, times 0 and 1).
const Eigen::Vector4d kLegKeys[6] = {
    Eigen::Vector4d(0, 0, 0, 0), Q(10, Eigen::Vector3d(1, 1, 0)).coeffs(), Eigen::Vector4d(0, 0.5, 0, 0),
    Eigen::Vector4d(0, 0.3, 0, 0), Q(90, Eigen::Vector3d::UnitY()).coeffs(), Eigen::Vector4d(0, 0, 0, 0)};

// The node transforms at time t per the glTF spec, computed here by hand.
std::vector<NodeTrs> AtTime(double t) {
  Scene scene;
  std::vector<NodeTrs> trs = scene.trs;
  const double s = std::clamp(t, 0.0, 1.0), s2 = s * s, s3 = s2 * s;
  const Eigen::Vector4d leg = (2 * s3 - 3 * s2 + 1) * kLegKeys[1] + (s3 - 2 * s2 + s) * kLegKeys[2] +
                              (-2 * s3 + 3 * s2) * kLegKeys[4] + (s3 - s2) * kLegKeys[3];
  trs[3].r = Eigen::Quaterniond(leg.normalized());  // coeffs() order x, y, z, w.
  trs[1].t = Eigen::Vector3d(0, t < 0.5 ? 0 : t < 1.0 ? 10 : 20, 100);  // STEP.
  trs[2].r = Q(30 + 60 * s, Eigen::Vector3d::UnitZ());                    // LINEAR slerp.
  return trs;
}

std::string TinyFile(Builder* b) {
  Scene scene;
  const std::vector<Eigen::Matrix4d> rest = Worlds(scene.trs);
  // Skin 0 joints: leg, hip, spine (not in preorder on purpose).
  const int skin_nodes[3] = {3, 1, 4};
  std::vector<float> ibm;
  for (int n : skin_nodes) {
    const Eigen::Matrix4d inv = rest[n].inverse();
    for (int e = 0; e < 16; ++e) ibm.push_back(static_cast<float>(inv(e % 4, e / 4)));
  }
  const int ibm_accessor = b->Floats(ibm, "MAT4", 16);
  // Primitive 0: 4 vertices, u8 joints, normalized u16 weights, u16 indices.
  const int p0_pos = b->Floats({0.f, 0.f, 1.f, 0.1f, -0.3f, 1.f, 0.f, 0.5f, 1.2f, 0.2f, 0.1f, 0.9f}, "VEC3", 3);
  const int p0_joints = b->Add(std::vector<uint8_t>{0, 1, 0, 0, 0, 0, 0, 0, 2, 1, 0, 0, 2, 0, 0, 0},
                               5121, "VEC4", 4);
  const int p0_weights = b->Add(std::vector<uint16_t>{32768, 32767, 0, 0, 65535, 0, 0, 0, 49151, 16384, 0, 0,
                                                      65535, 0, 0, 0},
                                5123, "VEC4", 4, ",\"normalized\":true");
  const int p0_idx = b->Add(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, 5123, "SCALAR", 1);
  // Primitive 1: 3 vertices (non-indexed), u16 joints, float weights, sparse POSITION.
  const int p1_pos_base = b->View(std::vector<float>{0, 0, 0, 1, 1, 1, 0.3f, 0.2f, 1.1f}.data(), 36);
  const int sparse_idx = b->View(std::vector<uint16_t>{1, 0}.data(), 2);
  const int sparse_val = b->View(std::vector<float>{-0.1f, -0.2f, 0.8f}.data(), 12);
  b->accessors.push_back("{\"bufferView\":" + std::to_string(p1_pos_base) +
                         ",\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"sparse\":{\"count\":1,"
                         "\"indices\":{\"bufferView\":" + std::to_string(sparse_idx) +
                         ",\"componentType\":5123},\"values\":{\"bufferView\":" + std::to_string(sparse_val) + "}}}");
  const int p1_pos = static_cast<int>(b->accessors.size()) - 1;
  const int p1_joints = b->Add(std::vector<uint16_t>{1, 0, 0, 0, 0, 2, 0, 0, 2, 0, 0, 0}, 5123, "VEC4", 4);
  const int p1_weights = b->Floats({1, 0, 0, 0, 0.25f, 0.75f, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
  // Animation samplers.
  std::vector<float> leg;
  for (const Eigen::Vector4d& k : kLegKeys) {
    for (int c = 0; c < 4; ++c) leg.push_back(static_cast<float>(k[c]));
  }
  const int t01 = b->Times({0.f, 1.f});
  const int t_step = b->Times({0.f, 0.5f, 1.f});
  const int leg_out = b->Floats(leg, "VEC4", 4);
  const int hip_out = b->Floats({0, 0, 100, 0, 10, 100, 0, 20, 100}, "VEC3", 3);
  std::vector<float> helper;
  for (double deg : {30.0, 90.0}) {
    const Eigen::Quaterniond q = Q(deg, Eigen::Vector3d::UnitZ());
    for (double c : {q.x(), q.y(), q.z(), q.w()}) helper.push_back(static_cast<float>(c));
  }
  const int helper_out = b->Floats(helper, "VEC4", 4);
  const int spine_scale = b->Floats({2, 2, 2, 2, 2, 2}, "VEC3", 3);
  const int varying_scale = b->Floats({1, 1, 1, 1, 2, 1}, "VEC3", 3);
  auto s = [](int i) { return std::to_string(i); };
  auto node = [&](const char* name, const NodeTrs& t, const std::string& extra) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "{\"name\":\"%s\",\"translation\":[%.17g,%.17g,%.17g],\"rotation\":%s,\"scale\":[%.17g,%.17g,%.17g]%s}",
                  name, t.t.x(), t.t.y(), t.t.z(), Vec(t.r).c_str(), t.s.x(), t.s.y(), t.s.z(), extra.c_str());
    return std::string(buf);
  };
  const std::string body =
      "\"scene\":0,\"scenes\":[{\"nodes\":[0,5,6]}],\"nodes\":[" + node("Armature", scene.trs[0], ",\"children\":[1]") +
      "," + node("hip", scene.trs[1], ",\"children\":[2,4]") + "," + node("helper", scene.trs[2], ",\"children\":[3]") +
      "," + node("leg", scene.trs[3], "") + "," + node("spine", scene.trs[4], "") + "," +
      node("body", scene.trs[5], ",\"mesh\":0,\"skin\":0") + "," + node("other", scene.trs[6], "") +
      "],\"skins\":[{\"joints\":[3,1,4],\"inverseBindMatrices\":" + s(ibm_accessor) +
      "},{\"name\":\"two_roots\",\"joints\":[4,3]},{\"name\":\"two_trees\",\"joints\":[3,6]}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" + s(p0_pos) + ",\"JOINTS_0\":" + s(p0_joints) +
      ",\"WEIGHTS_0\":" + s(p0_weights) + "},\"indices\":" + s(p0_idx) + "},{\"attributes\":{\"POSITION\":" +
      s(p1_pos) + ",\"JOINTS_0\":" + s(p1_joints) + ",\"WEIGHTS_0\":" + s(p1_weights) + "}}]}],"
      "\"animations\":[{\"name\":\"clip\",\"samplers\":["
      "{\"input\":" + s(t01) + ",\"output\":" + s(leg_out) + ",\"interpolation\":\"CUBICSPLINE\"},"
      "{\"input\":" + s(t_step) + ",\"output\":" + s(hip_out) + ",\"interpolation\":\"STEP\"},"
      "{\"input\":" + s(t01) + ",\"output\":" + s(helper_out) + "},"
      "{\"input\":" + s(t01) + ",\"output\":" + s(spine_scale) + "},"
      "{\"input\":" + s(t01) + ",\"output\":" + s(varying_scale) + "}],"
      "\"channels\":[{\"sampler\":0,\"target\":{\"node\":3,\"path\":\"rotation\"}},"
      "{\"sampler\":1,\"target\":{\"node\":1,\"path\":\"translation\"}},"
      "{\"sampler\":2,\"target\":{\"node\":2,\"path\":\"rotation\"}},"
      "{\"sampler\":3,\"target\":{\"node\":4,\"path\":\"scale\"}},"
      "{\"sampler\":4,\"target\":{\"node\":0,\"path\":\"scale\"}}]}]";
  return b->Json(body);
}

}  // namespace tiny

TEST(GltfReaderTiny, SkeletonBakesNodesAndScales) {
  tiny::Builder b;
  GltfDocument doc;
  Status status = GltfDocument::Parse(tiny::TinyFile(&b), "tiny.gltf", "", &doc);
  ASSERT_TRUE(status.ok()) << status.message();
  GltfCharacter c;
  status = ReadGltfCharacter(doc, {}, &c);
  ASSERT_TRUE(status.ok()) << status.message();
  // Preorder hip, leg (below the non-joint helper), spine.
  ASSERT_EQ(c.skeleton.num_joints(), 3);
  EXPECT_EQ(c.skeleton.name(0), "hip");
  EXPECT_EQ(c.skeleton.name(1), "leg");
  EXPECT_EQ(c.skeleton.name(2), "spine");
  EXPECT_EQ(c.skeleton.parent(1), 0);
  EXPECT_EQ(c.skeleton.parent(2), 0);
  EXPECT_EQ(c.skin_joints, (std::vector<int>{1, 0, 2}));
  EXPECT_EQ(c.joint_nodes, (std::vector<int>{1, 3, 4}));
  // Offsets: the parent's accumulated scale (0.01) times the chain translation.
  tiny::Scene scene;
  const Eigen::Vector3d leg_offset = 0.01 * (scene.trs[2].t + scene.trs[2].r * scene.trs[3].t);
  EXPECT_LT((c.skeleton.offset(1) - leg_offset).norm(), 1e-15);
  EXPECT_LT((c.skeleton.offset(0) - 0.01 * (scene.trs[0].r * scene.trs[1].t)).norm(), 1e-15);
  EXPECT_LT(c.skeleton.rest_rotation(1).angularDistance(scene.trs[2].r), 1e-15);
  EXPECT_LT(c.skeleton.rest_rotation(0).angularDistance(scene.trs[0].r), 1e-15);
  EXPECT_LT(c.rest_pose.rotations[1].angularDistance(scene.trs[3].r), 1e-15);
  // Mesh: 4 + 3 vertices, 2 + 1 triangles, the sparse vertex substituted.
  ASSERT_EQ(c.mesh.num_vertices(), 7);
  EXPECT_EQ(c.triangles.cols(), 3);
  EXPECT_EQ(c.triangles.col(2), Eigen::Vector3i(4, 5, 6));
  EXPECT_LT((c.mesh.rest_positions().col(5) - Eigen::Vector3d(-0.1, -0.2, 0.8)).norm(), 1e-6);
  EXPECT_NEAR(c.bind_scale, 1.0, 1e-6);
  // The one warning: the tiny mesh has no NORMAL, so its normals are computed.
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("area-weighted vertex normals"), std::string::npos) << c.warnings[0];
  EXPECT_TRUE(c.mesh.has_normals());
  EXPECT_EQ(c.mesh.num_joints(), 3);
  ASSERT_EQ(c.animation_names, std::vector<std::string>{"clip"});
}

TEST(GltfReaderTiny, SamplersAndSkinningMatchTheSpec) {
  tiny::Builder b;
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Parse(tiny::TinyFile(&b), "tiny.gltf", "", &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  // Default rate: the smallest key spacing (0.5 s) -> 2 fps, 3 frames.
  Motion motion;
  std::vector<std::string> warnings;
  ASSERT_TRUE(ReadGltfAnimation(doc, c, {}, &motion, &warnings).ok());
  EXPECT_EQ(motion.frame_rate, 2.0);
  EXPECT_EQ(motion.num_frames(), 3);
  // The varying scale on the Armature is ignored with a warning; the constant one used.
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("scale of node 0"), std::string::npos) << warnings[0];
  GltfAnimationOptions options;
  options.animation = "clip";
  options.frame_rate = 8.0;
  ASSERT_TRUE(ReadGltfAnimation(doc, c, options, &motion).ok());
  ASSERT_EQ(motion.num_frames(), 9);
  const tinygltf::Model& m = doc.model();
  const int ibm_accessor = m.skins[0].inverseBindMatrices;
  const std::vector<float> ibm = Floats(m, ibm_accessor);
  FkData fk(c.skeleton);
  std::vector<Eigen::Isometry3d> transforms;
  for (int f = 0; f < motion.num_frames(); ++f) {
    const std::vector<Eigen::Matrix4d> world = tiny::Worlds(tiny::AtTime(f / 8.0));
    ForwardKinematics(c.skeleton, motion.frames[f], &fk);
    for (int j = 0; j < 3; ++j) {
      const Eigen::Matrix4d& g = world[c.joint_nodes[j]];
      // 1e-6: float key data.
      EXPECT_LT((fk.world_positions[j] - g.topRightCorner<3, 1>()).norm(), 1e-6) << "frame " << f;
      const Eigen::Matrix3d rotation = g.topLeftCorner<3, 3>() / g.topLeftCorner<3, 3>().col(0).norm();
      EXPECT_LT((fk.world_rotations[j].toRotationMatrix() - rotation).norm(), 1e-6) << "frame " << f << " joint " << j;
    }
    // Skinning of the 4 vertices of primitive 0 by glTF's formula.
    ComputeSkinningTransforms(c.mesh, fk, &transforms);
    const std::vector<float> pos = Floats(m, m.meshes[0].primitives[0].attributes.at("POSITION"));
    const std::vector<float> joints = Floats(m, m.meshes[0].primitives[0].attributes.at("JOINTS_0"));
    const std::vector<float> weights = Floats(m, m.meshes[0].primitives[0].attributes.at("WEIGHTS_0"));
    for (int v = 0; v < 4; ++v) {
      Eigen::Vector4d sum = Eigen::Vector4d::Zero();
      double total = 0;
      for (int k = 0; k < 4; ++k) {
        const int skin_joint = static_cast<int>(joints[4 * v + k]);
        Eigen::Matrix4d inv_bind;
        for (int e = 0; e < 16; ++e) inv_bind(e % 4, e / 4) = ibm[16 * skin_joint + e];
        sum += weights[4 * v + k] * (world[m.skins[0].joints[skin_joint]] * inv_bind *
                                     Eigen::Vector4d(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1));
        total += weights[4 * v + k];
      }
      EXPECT_LT((SkinPosition(c.mesh, transforms, v) - sum.head<3>() / total).norm(), 1e-6)
          << "frame " << f << " vertex " << v;
    }
  }
}

TEST(GltfReaderTiny, SeveralRootsGetTheirCommonAncestorOrASyntheticRoot) {
  tiny::Builder b;
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Parse(tiny::TinyFile(&b), "tiny.gltf", "", &doc).ok());
  GltfCharacter c;
  GltfReadOptions options;
  options.skin = "two_roots";  // spine and leg: their common ancestor hip becomes the root.
  Status status = ReadGltfCharacter(doc, options, &c);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(c.skeleton.num_joints(), 3);
  EXPECT_EQ(c.skeleton.name(0), "hip");
  EXPECT_EQ(c.skin_joints, (std::vector<int>{2, 1}));
  EXPECT_EQ(c.mesh.num_vertices(), 0);
  options.skin = "2";  // leg and 'other' are in different trees: a synthetic root.
  status = ReadGltfCharacter(doc, options, &c);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(c.skeleton.num_joints(), 3);
  EXPECT_EQ(c.skeleton.name(0), "gltf_root");
  EXPECT_EQ(c.joint_nodes[0], -1);
  // FK still gives glTF's world positions.
  Motion motion;
  ASSERT_TRUE(ReadGltfAnimation(doc, c, {}, &motion).ok());
  FkData fk(c.skeleton);
  ForwardKinematics(c.skeleton, motion.frames[1], &fk);
  const std::vector<Eigen::Matrix4d> world = tiny::Worlds(tiny::AtTime(0.5));
  for (int j = 1; j < 3; ++j) {
    EXPECT_LT((fk.world_positions[j] - world[c.joint_nodes[j]].topRightCorner<3, 1>()).norm(), 1e-6);
  }
  options.skin = "nope";
  status = ReadGltfCharacter(doc, options, &c);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), "tiny.gltf: no skin named 'nope' (skins: '', 'two_roots', 'two_trees')");
}

// A mesh without NORMAL (as Fox has) gets area-weighted vertex normals and a warning: the
// test character is stored per face with one vertex per joint, so each vertex lies on one
// triangle and its normal is that triangle's (b - a) x (c - a), normalized.
TEST(GltfReaderTiny, AMeshWithoutNormalsGetsAreaWeightedNormals) {
  const std::string path = testing::TempPath("no_normals.gltf");
  testing::WriteTestCharacter(path, 30.0);
  ASSERT_EQ(testing::ReadTextFile(path).find("NORMAL"), std::string::npos);
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(path, GltfReadOptions(), &c).ok());
  ASSERT_TRUE(c.mesh.has_normals());
  bool warned = false;
  for (const std::string& w : c.warnings) warned |= w.find("area-weighted vertex normals") != std::string::npos;
  EXPECT_TRUE(warned);
  const Eigen::Matrix3Xd& x = c.mesh.rest_positions();
  int checked = 0;
  for (Eigen::Index t = 0; t < c.triangles.cols(); ++t) {
    const Eigen::Vector3d n = (x.col(c.triangles(1, t)) - x.col(c.triangles(0, t)))
                                  .cross(x.col(c.triangles(2, t)) - x.col(c.triangles(0, t)));
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d got = c.mesh.rest_normals().col(c.triangles(k, t));
      EXPECT_NEAR(got.norm(), 1.0, 1e-12);
      if (n.norm() < 1e-9) continue;  // Collinear joints: no area, +y.
      EXPECT_LT((got - n.normalized()).norm(), 1e-9) << "triangle " << t;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
}

// tests/data/bad/bad_gltf_*: each fails (through ReadMotionFile, as `mocapsolve info`
// reads it) with one line "<path>: ..." containing its asset.extras "expect-error"; the
// CLI exits 1 with that one line.
TEST(GltfBadFiles, AnnotatedBadFilesFailWithOneLine) {
  int checked = 0;
  for (const char* name : {"bad_gltf_accessor_range.gltf", "bad_gltf_skin_joint.gltf", "bad_gltf_ibm_count.gltf",
                           "bad_gltf_weight_joint.gltf", "bad_gltf_truncated.glb", "bad_gltf_version.glb",
                           "bad_gltf_self_child.gltf", "bad_gltf_node_cycle.gltf"}) {
    const std::string path = testing::SourcePath(std::string("tests/data/bad/") + name);
    std::string bytes;
    ASSERT_TRUE(ReadFileToString(path, &bytes).ok()) << path;
    const std::string key = "\"expect-error\":";
    size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos) << name << " has no expect-error annotation";
    at = bytes.find('"', at + key.size()) + 1;
    const std::string expected = bytes.substr(at, bytes.find('"', at) - at);
    Skeleton skeleton;
    Motion motion;
    const Status status = ReadMotionFile(path, MotionFileOptions(), &skeleton, &motion);
    ASSERT_FALSE(status.ok()) << name;
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
    EXPECT_EQ(status.message().rfind(path + ": ", 0), 0u) << status.message();
    EXPECT_NE(status.message().find(expected), std::string::npos) << status.message() << " vs " << expected;
    std::string output;
    EXPECT_EQ(testing::RunCli("info " + path, &output), 1) << output;
    EXPECT_EQ(output, "mocapsolve info: " + status.message() + "\n");
    ++checked;
  }
  EXPECT_EQ(checked, 8);
}

// Damaged copies of the tiny file (JSON) and of a GLB written from it never crash, and
// every failure is one line.
TEST(GltfBadFiles, DamagedFilesFailCleanly) {
  tiny::Builder b;
  const std::string json = tiny::TinyFile(&b);
  GltfDocument doc;
  ASSERT_TRUE(GltfDocument::Parse(json, "tiny.gltf", "", &doc).ok());
  GltfCharacter c;
  ASSERT_TRUE(ReadGltfCharacter(doc, {}, &c).ok());
  Motion motion;
  ASSERT_TRUE(ReadGltfAnimation(doc, c, {}, &motion).ok());
  std::string glb;
  ASSERT_TRUE(SerializeGltfWithAnimation(doc, c, motion, "copy", true, &glb).ok());
  std::mt19937 rng(5);
  int failures = 0, successes = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const bool binary = trial % 2 == 1;
    std::string bytes;
    if (binary) {  // Damage the JSON chunk and the binary data, keeping the header length.
      bytes = glb;
      for (int k = 0; k < 3; ++k) bytes[20 + rng() % (bytes.size() - 20)] = static_cast<char>(rng() & 0xff);
    } else {
      bytes = testing::RandomlyDamaged(json, "0123456789[]{},:.-\"e", &rng);
    }
    GltfDocument d;
    Status status = GltfDocument::Parse(bytes, "damaged", "", &d);
    GltfCharacter dc;
    if (status.ok()) status = ReadGltfCharacter(d, {}, &dc);
    Motion dm;
    if (status.ok() && !dc.animation_names.empty()) status = ReadGltfAnimation(d, dc, {}, &dm);
    if (status.ok()) {
      ++successes;
      EXPECT_TRUE(ValidateMotion(dc.skeleton, dm).ok() || dc.animation_names.empty());
    } else {
      ++failures;
      ASSERT_EQ(status.message().find('\n'), std::string::npos) << status.message();
      ASSERT_EQ(status.message().rfind("damaged: ", 0), 0u) << status.message();
    }
  }
  std::printf("%d damaged files rejected, %d still readable\n", failures, successes);
  EXPECT_GT(failures, 0);
}
}  // namespace
}  // namespace mocapsolve
