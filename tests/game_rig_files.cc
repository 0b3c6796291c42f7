#include "tests/game_rig_files.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

namespace mocapsolve::testing {
namespace {

// Mixamo core name -> Unreal, Rigify, Biped, VRM names (sides added by GameRigJointName).
const std::map<std::string, std::vector<std::string>>& CoreNames() {
  static const auto* table = new std::map<std::string, std::vector<std::string>>{
      {"Hips", {"pelvis", "spine", "Pelvis", "Hips"}},
      {"Spine", {"spine_01", "spine.001", "Spine", "Spine"}},
      {"Spine1", {"spine_02", "spine.002", "Spine1", "Chest"}},
      {"Spine2", {"spine_03", "spine.003", "Spine2", "UpperChest"}},
      {"Neck", {"neck_01", "spine.004", "Neck", "Neck"}},
      {"Head", {"head", "spine.006", "Head", "Head"}},
      {"HeadTop_End", {"head_end", "spine.006_end", "HeadNub", "Head_end"}},
      {"Shoulder", {"clavicle", "shoulder", "Clavicle", "Shoulder"}},
      {"Arm", {"upperarm", "upper_arm", "UpperArm", "UpperArm"}},
      {"ForeArm", {"lowerarm", "forearm", "Forearm", "LowerArm"}},
      {"Hand", {"hand", "hand", "Hand", "Hand"}},
      {"UpLeg", {"thigh", "thigh", "Thigh", "UpperLeg"}},
      {"Leg", {"calf", "shin", "Calf", "LowerLeg"}},
      {"Foot", {"foot", "foot", "Foot", "Foot"}},
      {"ToeBase", {"ball", "toe", "Toe0", "ToeBase"}},
      {"Toe_End", {"ball_end", "toe_end", "Toe0Nub", "ToeBase_end"}},
  };
  return *table;
}

Eigen::Matrix4d LocalMatrix(const tinygltf::Node& node) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (node.matrix.size() == 16) {
    for (int k = 0; k < 16; ++k) m(k % 4, k / 4) = node.matrix[k];
    return m;
  }
  if (node.rotation.size() == 4) {
    m.topLeftCorner<3, 3>() =
        Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2])
            .normalized()
            .toRotationMatrix();
  }
  if (node.scale.size() == 3) {
    for (int c = 0; c < 3; ++c) m.col(c).head<3>() *= node.scale[c];
  }
  if (node.translation.size() == 3) m.col(3).head<3>() << node.translation[0], node.translation[1], node.translation[2];
  return m;
}

// A rigid transform with a uniform scale as the node's TRS.
void SetLocalMatrix(const Eigen::Matrix4d& m, tinygltf::Node* node) {
  node->matrix.clear();
  const double s = m.col(0).head<3>().norm();
  const Eigen::Quaterniond q(Eigen::Matrix3d(m.topLeftCorner<3, 3>() / s));
  node->rotation = {q.x(), q.y(), q.z(), q.w()};
  node->translation = {m(0, 3), m(1, 3), m(2, 3)};
  if (std::abs(s - 1.0) > 1e-9) {
    node->scale = {s, s, s};
  } else {
    node->scale.clear();
  }
}

void Worlds(const tinygltf::Model& model, int node, const Eigen::Matrix4d& parent, std::vector<Eigen::Matrix4d>* world) {
  (*world)[node] = parent * LocalMatrix(model.nodes[node]);
  for (int c : model.nodes[node].children) Worlds(model, c, (*world)[node], world);
}

int NodeNamed(const tinygltf::Model& model, const std::string& name) {
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    if (model.nodes[i].name == name) return static_cast<int>(i);
  }
  ADD_FAILURE() << "no node " << name;
  return -1;
}

// Edits a model's node graph keeping world transforms.
class Graph {
 public:
  explicit Graph(tinygltf::Model* model) : m_(*model), parent_(model->nodes.size(), -1) {
    for (size_t i = 0; i < m_.nodes.size(); ++i) {
      for (int c : m_.nodes[i].children) parent_[c] = static_cast<int>(i);
    }
    world_.assign(m_.nodes.size(), Eigen::Matrix4d::Identity());
    for (size_t i = 0; i < m_.nodes.size(); ++i) {
      if (parent_[i] < 0) Worlds(m_, static_cast<int>(i), Eigen::Matrix4d::Identity(), &world_);
    }
  }
  int parent(int node) const { return parent_[node]; }
  const Eigen::Matrix4d& world(int node) const { return world_[node]; }
  // A new node with world transform `world` under `parent`; a skin joint when `joint`.
  // `first`: before the parent's other children (exporters often sort them by name, and
  // "ORG-" < "upper_arm_fk" sort before or after "DEF-" as it comes).
  int Add(const std::string& name, int parent, const Eigen::Matrix4d& world, bool joint, bool first = false) {
    tinygltf::Node node;
    node.name = name;
    SetLocalMatrix(world_[parent].inverse() * world, &node);
    const int index = static_cast<int>(m_.nodes.size());
    m_.nodes.push_back(node);
    std::vector<int>& children = m_.nodes[parent].children;
    children.insert(first ? children.begin() : children.end(), index);
    parent_.push_back(parent);
    world_.push_back(world);
    if (joint) new_joints.push_back(index);
    return index;
  }
  void Reparent(int node, int new_parent) {
    std::vector<int>& old_children = m_.nodes[parent_[node]].children;
    old_children.erase(std::find(old_children.begin(), old_children.end(), node));
    m_.nodes[new_parent].children.push_back(node);
    SetLocalMatrix(world_[new_parent].inverse() * world_[node], &m_.nodes[node]);
    parent_[node] = new_parent;
  }
  std::vector<int> new_joints;

 private:
  tinygltf::Model& m_;
  std::vector<int> parent_;
  std::vector<Eigen::Matrix4d> world_;
};

Eigen::Matrix4d WithTranslation(Eigen::Matrix4d m, const Eigen::Vector3d& t) {
  m.col(3).head<3>() = t;
  return m;
}

}  // namespace

std::string SchemeName(GameRigScheme scheme) {
  switch (scheme) {
    case GameRigScheme::kUnreal: return "unreal";
    case GameRigScheme::kRigify: return "rigify";
    case GameRigScheme::kBiped: return "biped";
    case GameRigScheme::kVrm: return "vrm";
    case GameRigScheme::kRandom: return "random";
  }
  return "";
}

std::string GameRigJointName(const std::string& mixamo_name, const GameRigOptions& options) {
  std::string core = mixamo_name.substr(mixamo_name.find(':') == std::string::npos ? 0 : mixamo_name.find(':') + 1);
  if (options.scheme == GameRigScheme::kRandom) {
    uint32_t hash = 2166136261u;  // FNV-1a: the same digits for the same name on every run.
    for (char c : core) hash = (hash ^ static_cast<unsigned char>(c)) * 16777619u;
    return "b" + std::to_string(1000000 + hash % 9000000);
  }
  int side = 0;  // -1 left, +1 right.
  if (core.rfind("Left", 0) == 0) side = -1, core = core.substr(4);
  if (core.rfind("Right", 0) == 0) side = 1, core = core.substr(5);
  const int s = static_cast<int>(options.scheme);
  std::string name;
  const auto found = CoreNames().find(core);
  if (found != CoreNames().end()) {
    name = found->second[s];
  } else if (core.rfind("Hand", 0) == 0 && core.size() > 5) {  // HandIndex2: finger, phalanx.
    std::string finger = core.substr(4, core.size() - 5);
    const int phalanx = core.back() - '0';
    std::string lower = finger;
    std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
    const std::vector<std::string> biped_fingers = {"Thumb", "Index", "Middle", "Ring", "Pinky"};
    const int index = static_cast<int>(std::find(biped_fingers.begin(), biped_fingers.end(), finger) - biped_fingers.begin());
    switch (options.scheme) {
      case GameRigScheme::kUnreal: name = lower + "_0" + std::to_string(phalanx); break;
      case GameRigScheme::kRigify: name = (index == 0 ? "" : "f_") + lower + ".0" + std::to_string(phalanx); break;
      case GameRigScheme::kBiped:
        name = "Finger" + std::to_string(index) + (phalanx == 1 ? "" : std::to_string(phalanx - 1)); break;
      default: name = finger + std::to_string(phalanx); break;
    }
  } else {
    name = core;
  }
  const bool lower_case = options.lower_case_sides;
  switch (options.scheme) {
    case GameRigScheme::kUnreal: return name + (side < 0 ? "_l" : side > 0 ? "_r" : "");
    case GameRigScheme::kRigify:
      return "DEF-" + name + (side < 0 ? (lower_case ? ".l" : ".L") : side > 0 ? (lower_case ? ".r" : ".R") : "");
    case GameRigScheme::kBiped: return std::string("Bip01 ") + (side < 0 ? "L " : side > 0 ? "R " : "") + name;
    case GameRigScheme::kVrm: return std::string("J_Bip_") + (side < 0 ? "L_" : side > 0 ? "R_" : "C_") + name;
    case GameRigScheme::kRandom: break;
  }
  return name;
}

void MakeGameRig(const std::string& glb, const GameRigOptions& options, GltfDocument* document,
                 GltfCharacter* character) {
  GltfDocument source;
  Status status = GltfDocument::Read(glb, &source);
  ASSERT_TRUE(status.ok()) << status.message();
  tinygltf::Model m = source.model();
  // Only the skeleton and the mesh matter here.
  m.images.clear();
  m.textures.clear();
  m.samplers.clear();
  m.materials.clear();
  m.animations.clear();
  for (tinygltf::Mesh& mesh : m.meshes) {
    for (tinygltf::Primitive& p : mesh.primitives) p.material = -1;
  }
  ASSERT_EQ(m.skins.size(), 1u);
  Graph graph(&m);
  const auto node = [&](const std::string& mixamo) { return NodeNamed(m, "mixamorig:" + mixamo); };
  const int hips = node("Hips");
  ASSERT_GE(hips, 0);
  const int top = graph.parent(hips);
  ASSERT_GE(top, 0) << glb << ": the hips have no node above them";
  ASSERT_LT(graph.parent(top), 0) << glb << ": the node above the hips is not a scene root";
  ASSERT_EQ(m.nodes[top].scale.size(), 3u);
  const auto floor_root = [&](const std::string& name) {
    const int root = graph.Add(name, top, graph.world(top), true);
    graph.Reparent(hips, root);
    return root;
  };
  const auto ik = [&](const std::string& name, int parent, const std::string& at) {
    return graph.Add(name, parent, graph.world(node(at)), true);
  };
  switch (options.scheme) {
    case GameRigScheme::kUnreal: {
      const int root = floor_root("root");
      const int foot_root = graph.Add("ik_foot_root", root, graph.world(root), true);
      ik("ik_foot_l", foot_root, "LeftFoot");
      ik("ik_foot_r", foot_root, "RightFoot");
      const int hand_root = graph.Add("ik_hand_root", root, graph.world(root), true);
      const int gun = ik("ik_hand_gun", hand_root, "RightHand");
      ik("ik_hand_l", gun, "LeftHand");
      ik("ik_hand_r", gun, "RightHand");
      break;
    }
    case GameRigScheme::kRigify: {
      const int root = floor_root("root");
      if (options.rigify_controls) {  // Whole copies of each limb's subtree, before the DEF- one.
        for (const std::string limb : {"LeftArm", "RightArm", "LeftUpLeg", "RightUpLeg"}) {
          const int top_joint = node(limb);
          for (const std::string kind : {"ORG", "fk", "tweak"}) {
            std::vector<std::pair<int, int>> stack = {{top_joint, graph.parent(top_joint)}};  // (original, new parent)
            while (!stack.empty()) {
              const auto [original, parent] = stack.back();
              stack.pop_back();
              const std::string def = GameRigJointName(m.nodes[original].name, options);
              const std::string base = def.rfind("DEF-", 0) == 0 ? def.substr(4) : def;
              const size_t dot = base.rfind('.');
              const std::string name = kind == "ORG" ? "ORG-" + base
                                                     : base.substr(0, dot) + "_" + kind + base.substr(dot);
              const int copy = graph.Add(name, parent, graph.world(original), true, original == top_joint);
              for (int child : m.nodes[original].children) stack.push_back({child, copy});
            }
          }
        }
        break;
      }
      for (const std::string side : {"Left", "Right"}) {
        for (const std::vector<std::string>& chain : {std::vector<std::string>{"Arm", "ForeArm", "Hand"},
                                                      std::vector<std::string>{"UpLeg", "Leg", "Foot", "ToeBase"}}) {
          int org = graph.parent(node(side + chain[0])), mch = root;
          for (const std::string& bone : chain) {
            const std::string def = GameRigJointName(side + bone, options);  // DEF-upper_arm.L
            const std::string base = def.substr(4);
            const size_t dot = base.rfind('.');
            org = ik("ORG-" + base, org, side + bone);
            mch = ik("MCH-" + base.substr(0, dot) + "_ik" + base.substr(dot), mch, side + bone);
          }
        }
      }
      break;
    }
    case GameRigScheme::kBiped: {
      const int bip01 = graph.Add("Bip01", top, WithTranslation(graph.world(top), graph.world(hips).col(3).head<3>()), true);
      graph.Reparent(hips, bip01);
      const Eigen::Vector3d h = graph.world(hips).col(3).head<3>();
      graph.Add("Bip01 Footsteps", bip01, WithTranslation(graph.world(top), Eigen::Vector3d(h.x(), 0.0, h.z())), true);
      graph.Reparent(node("LeftShoulder"), node("Neck"));
      graph.Reparent(node("RightShoulder"), node("Neck"));
      break;
    }
    case GameRigScheme::kVrm:
      floor_root("Root");
      break;
    case GameRigScheme::kRandom: {
      const int root = floor_root(GameRigJointName("Root", options));
      graph.Reparent(node("LeftFoot"), root);
      graph.Reparent(node("RightFoot"), root);
      break;
    }
  }
  for (tinygltf::Node& n : m.nodes) {
    if (n.name.rfind("mixamorig:", 0) == 0) n.name = GameRigJointName(n.name, options);
  }
  // The top node's scale and rotation; the nodes below keep their world transforms.
  const double k = m.nodes[top].scale[0] / options.armature_scale;
  std::vector<int> below = m.nodes[top].children;
  for (size_t i = 0; i < below.size(); ++i) {
    tinygltf::Node& n = m.nodes[below[i]];
    ASSERT_TRUE(n.matrix.empty());
    for (double& t : n.translation) t *= k;
    below.insert(below.end(), n.children.begin(), n.children.end());
  }
  const Eigen::Matrix4d old_top = LocalMatrix(m.nodes[top]);
  const Eigen::Matrix3d r_top = old_top.topLeftCorner<3, 3>() / old_top.col(0).head<3>().norm();
  const Eigen::Matrix3d r_new =
      options.z_up ? Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix() : Eigen::Matrix3d::Identity();
  Eigen::Matrix4d q = Eigen::Matrix4d::Identity();
  q.topLeftCorner<3, 3>() = r_new.transpose() * r_top;
  for (int c : m.nodes[top].children) SetLocalMatrix(q * LocalMatrix(m.nodes[c]), &m.nodes[c]);
  const Eigen::Quaterniond qn(r_new);
  m.nodes[top].rotation = {qn.x(), qn.y(), qn.z(), qn.w()};
  m.nodes[top].scale = {options.armature_scale, options.armature_scale, options.armature_scale};
  // Inverse bind matrices: the old ones rescaled, the new joints' from their rest transforms.
  std::vector<Eigen::Matrix4d> world(m.nodes.size(), Eigen::Matrix4d::Identity());
  Worlds(m, top, Eigen::Matrix4d::Identity(), &world);
  tinygltf::Skin& skin = m.skins[0];
  const tinygltf::Accessor old_accessor = m.accessors[skin.inverseBindMatrices];
  const tinygltf::BufferView& old_view = m.bufferViews[old_accessor.bufferView];
  const size_t stride = old_view.byteStride > 0 ? old_view.byteStride : 64;
  std::vector<float> ibm;
  for (size_t b = 0; b < skin.joints.size(); ++b) {
    float f[16];
    std::memcpy(f, m.buffers[old_view.buffer].data.data() + old_view.byteOffset + old_accessor.byteOffset + b * stride, 64);
    Eigen::Matrix4d mb;
    for (int e = 0; e < 16; ++e) mb(e % 4, e / 4) = f[e];
    mb.topRows<3>() *= k;
    for (int e = 0; e < 16; ++e) ibm.push_back(static_cast<float>(mb(e % 4, e / 4)));
  }
  for (int j : graph.new_joints) {
    skin.joints.push_back(j);
    const Eigen::Matrix4d inverse = world[j].inverse();
    for (int e = 0; e < 16; ++e) ibm.push_back(static_cast<float>(inverse(e % 4, e / 4)));
  }
  std::vector<unsigned char>& data = m.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = ibm.size() * sizeof(float);
  data.resize(data.size() + view.byteLength);
  std::memcpy(data.data() + view.byteOffset, ibm.data(), view.byteLength);
  m.bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.type = TINYGLTF_TYPE_MAT4;
  accessor.count = skin.joints.size();
  m.accessors.push_back(accessor);
  skin.inverseBindMatrices = static_cast<int>(m.accessors.size()) - 1;
  // A node above with the (non-uniform) scale.
  if (options.above_scale != Eigen::Vector3d::Ones()) {
    tinygltf::Node above;
    above.name = "Scaled";
    above.scale = {options.above_scale.x(), options.above_scale.y(), options.above_scale.z()};
    above.children = {top};
    m.nodes.push_back(above);
    for (tinygltf::Scene& scene : m.scenes) {
      std::replace(scene.nodes.begin(), scene.nodes.end(), top, static_cast<int>(m.nodes.size()) - 1);
    }
  }
  tinygltf::TinyGLTF writer;
  std::ostringstream bytes;
  ASSERT_TRUE(writer.WriteGltfSceneToStream(&m, bytes, /*prettyPrint=*/false, /*writeBinary=*/true));
  const std::string name = glb.substr(glb.rfind('/') + 1) + " as " + SchemeName(options.scheme);
  if (std::getenv("GAME_RIG_DUMP_DIR") != nullptr) {  // To look at a rig with the CLI.
    std::ofstream(std::string(std::getenv("GAME_RIG_DUMP_DIR")) + "/" + name + ".glb", std::ios::binary) << bytes.str();
  }
  status = GltfDocument::Parse(bytes.str(), name, "", document);
  ASSERT_TRUE(status.ok()) << status.message();
  status = ReadGltfCharacter(*document, GltfReadOptions(), character);
  ASSERT_TRUE(status.ok()) << status.message();
}

}  // namespace mocapsolve::testing
