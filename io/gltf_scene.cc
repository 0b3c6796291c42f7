#include "io/gltf_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>

#include <Eigen/SVD>
#include <tiny_gltf.h>

#include "kinematics/quote_token.h"

namespace mocapsolve::gltf_internal {
namespace {

std::string NodeLabel(const tinygltf::Model& model, int n) {
  std::string label = "node " + std::to_string(n);
  if (!model.nodes[n].name.empty()) label += " " + QuoteToken(model.nodes[n].name);
  return label;
}

bool AllFinite(const std::vector<double>& v) {
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

// Largest element count an accessor may declare (2^26 = 67M elements; the largest
// real characters hold well under a million vertices).
constexpr size_t kMaxAccessorCount = size_t{1} << 26;

double ReadComponent(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = *p;
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = static_cast<int8_t>(*p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t u;
      std::memcpy(&u, p, 2);
      return normalized ? u / 65535.0 : u;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t s;
      std::memcpy(&s, p, 2);
      return normalized ? std::max(s / 32767.0, -1.0) : s;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t u;
      std::memcpy(&u, p, 4);
      return u;
    }
    default:
      return std::numeric_limits<double>::quiet_NaN();
  }
}

const char* ComponentTypeName(int t) {
  switch (t) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float";
    default: return "unknown";
  }
}

// Checks that a buffer view holds `count` elements of `element_size` bytes from
// `offset` with `stride`, and returns the first byte.
Status ViewSpan(const tinygltf::Model& model, int view_index, size_t offset, size_t count,
                size_t element_size, size_t stride, const std::string& where,
                const unsigned char** data) {
  if (view_index < 0 || view_index >= static_cast<int>(model.bufferViews.size())) {
    return Status::Error(where + ": bufferView " + std::to_string(view_index) +
                         " out of range (" + std::to_string(model.bufferViews.size()) +
                         " buffer views)");
  }
  const tinygltf::BufferView& view = model.bufferViews[view_index];
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size())) {
    return Status::Error(where + ": bufferView " + std::to_string(view_index) + ": buffer " +
                         std::to_string(view.buffer) + " out of range");
  }
  const size_t buffer_size = model.buffers[view.buffer].data.size();
  if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
    return Status::Error(where + ": bufferView " + std::to_string(view_index) +
                         ": bytes [" + std::to_string(view.byteOffset) + ", " +
                         std::to_string(view.byteOffset + view.byteLength) +
                         ") exceed buffer " + std::to_string(view.buffer) + " of " +
                         std::to_string(buffer_size) + " bytes");
  }
  if (count > 0) {
    // offset + stride * (count - 1) + element_size <= byteLength, without overflow
    // (count <= kMaxAccessorCount and stride <= 255 + element_size keep it in range).
    const size_t need = offset + stride * (count - 1) + element_size;
    if (offset > view.byteLength || need > view.byteLength) {
      return Status::Error(where + ": needs " + std::to_string(need) + " bytes of bufferView " +
                           std::to_string(view_index) + ", which has " +
                           std::to_string(view.byteLength));
    }
  }
  *data = model.buffers[view.buffer].data.data() + view.byteOffset + offset;
  return Status::Ok();
}

}  // namespace

double UniformScale(const Eigen::Vector3d& s, bool* exact) {
  const double product = std::abs(s.x() * s.y() * s.z());
  const double uniform = std::cbrt(product);
  *exact = s.minCoeff() > 0.0 &&
           (s.array() - uniform).abs().maxCoeff() <= 1e-5 * std::max(uniform, 1e-300);
  return uniform;
}

double KeySpacing(const std::vector<double>& spacings) {
  if (spacings.empty()) return 0.0;
  const double smallest = *std::min_element(spacings.begin(), spacings.end());
  if (!(smallest > 0.0)) return 0.0;
  for (double d : spacings) {
    const double multiple = d / smallest;
    if (std::abs(multiple - std::round(multiple)) > 1e-3) return 0.0;
  }
  return smallest;
}

Similarity SimilarityFromMatrix(const Eigen::Matrix4d& m, bool* exact) {
  Similarity out;
  const Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
  out.translation = m.topRightCorner<3, 1>();
  const double det = a.determinant();
  out.scale = std::cbrt(std::abs(det));
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  const Eigen::Matrix3d v = svd.matrixV();
  if ((u * v.transpose()).determinant() < 0.0) u.col(2) = -u.col(2);
  const Eigen::Matrix3d r = u * v.transpose();
  out.rotation = Eigen::Quaterniond(r).normalized();
  const double tolerance = 1e-5 * std::max(out.scale, 1e-300);
  *exact = out.scale > 0.0 && det > 0.0 && (a - out.scale * r).cwiseAbs().maxCoeff() <= tolerance &&
           std::abs(m(3, 0)) + std::abs(m(3, 1)) + std::abs(m(3, 2)) + std::abs(m(3, 3) - 1.0) <= 1e-9;
  if (!(out.scale > 0.0)) out.scale = 1.0;  // Singular: keep a usable transform.
  return out;
}

Status BuildNodeGraph(const tinygltf::Model& model, const std::string& file, NodeGraph* graph,
                      std::vector<std::string>* warnings) {
  const int n = static_cast<int>(model.nodes.size());
  NodeGraph g;
  g.parent.assign(n, -1);
  g.local.resize(n);
  g.raw_scale.assign(n, Eigen::Vector3d::Ones());
  g.has_matrix.assign(n, false);
  for (int i = 0; i < n; ++i) {
    const tinygltf::Node& node = model.nodes[i];
    for (int child : node.children) {
      if (child < 0 || child >= n) {
        return Status::Error(file + ": " + NodeLabel(model, i) + ": child " +
                             std::to_string(child) + " out of range (" + std::to_string(n) +
                             " nodes)");
      }
      if (child == i) {
        return Status::Error(file + ": " + NodeLabel(model, i) + ": is its own child (the node graph must be a forest)");
      }
      if (g.parent[child] != -1) {
        return Status::Error(file + ": " + NodeLabel(model, child) +
                             ": has more than one parent (the node graph must be a forest)");
      }
      g.parent[child] = i;
    }
    const std::string where = file + ": " + NodeLabel(model, i);
    if (!AllFinite(node.matrix) || !AllFinite(node.rotation) || !AllFinite(node.scale) ||
        !AllFinite(node.translation)) {
      return Status::Error(where + ": non-finite transform");
    }
    Similarity& local = g.local[i];
    if (node.matrix.size() == 16) {
      Eigen::Matrix4d m;
      for (int k = 0; k < 16; ++k) m(k % 4, k / 4) = node.matrix[k];
      bool exact = true;
      local = SimilarityFromMatrix(m, &exact);
      g.has_matrix[i] = true;
      if (!exact && warnings != nullptr) {
        warnings->push_back(where + ": matrix is not a uniform-scale similarity; approximated");
      }
    } else {
      if (!node.matrix.empty()) return Status::Error(where + ": matrix must have 16 numbers");
      if (!node.translation.empty()) {
        if (node.translation.size() != 3) return Status::Error(where + ": translation must have 3 numbers");
        local.translation = Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]);
      }
      if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) return Status::Error(where + ": rotation must have 4 numbers");
        Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        if (std::abs(q.norm() - 1.0) > 1e-3) {
          return Status::Error(where + ": rotation is not a unit quaternion (norm " +
                               std::to_string(q.norm()) + ")");
        }
        local.rotation = q.normalized();
      }
      if (!node.scale.empty()) {
        if (node.scale.size() != 3) return Status::Error(where + ": scale must have 3 numbers");
        g.raw_scale[i] = Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]);
        bool exact = true;
        local.scale = UniformScale(g.raw_scale[i], &exact);
        if (!(local.scale > 0.0)) return Status::Error(where + ": zero scale");
        if (!exact && warnings != nullptr) {
          warnings->push_back(where + ": non-uniform or negative scale approximated by " +
                              std::to_string(local.scale));
        }
      }
    }
  }
  // Cycles: with one parent each, a cycle is a set of nodes none of which reaches a root.
  for (int i = 0; i < n; ++i) {
    int steps = 0;
    for (int k = i; k != -1; k = g.parent[k]) {
      if (++steps > n) {
        return Status::Error(file + ": " + NodeLabel(model, i) + ": is in a cycle of children");
      }
    }
  }
  *graph = std::move(g);
  return Status::Ok();
}

Status ReadAccessor(const tinygltf::Model& model, int index, int components,
                    const std::vector<int>& allowed_component_types, const std::string& file,
                    const std::string& field, std::vector<double>* values, size_t* count) {
  const std::string where = file + ": " + field + ": accessor " + std::to_string(index);
  if (index < 0 || index >= static_cast<int>(model.accessors.size())) {
    return Status::Error(file + ": " + field + ": accessor " + std::to_string(index) +
                         " out of range (" + std::to_string(model.accessors.size()) +
                         " accessors)");
  }
  const tinygltf::Accessor& a = model.accessors[index];
  const int type_components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
  if (type_components != components) {
    return Status::Error(where + ": has " + std::to_string(type_components) +
                         " components per element, expected " + std::to_string(components));
  }
  if (std::find(allowed_component_types.begin(), allowed_component_types.end(),
                a.componentType) == allowed_component_types.end()) {
    return Status::Error(where + ": component type " + ComponentTypeName(a.componentType) +
                         " (" + std::to_string(a.componentType) + ") not allowed here");
  }
  if (a.count > kMaxAccessorCount) {
    return Status::Error(where + ": count " + std::to_string(a.count) + " too large");
  }
  const size_t component_size =
      static_cast<size_t>(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType)));
  const size_t element_size = component_size * components;
  if (a.bufferView < 0) {
    // Zeros (plus sparse values): bound the size by the file's data so that a tiny file
    // cannot make us allocate gigabytes.
    size_t total = 0;
    for (const tinygltf::Buffer& b : model.buffers) total += b.data.size();
    if (a.count > 4 * total + 1024) {
      return Status::Error(where + ": count " + std::to_string(a.count) +
                           " without a bufferView is out of proportion to the file's " +
                           std::to_string(total) + " data bytes");
    }
  }
  std::vector<double> out(a.count * components, 0.0);
  if (a.bufferView >= 0) {
    if (a.bufferView >= static_cast<int>(model.bufferViews.size())) {
      return Status::Error(where + ": bufferView " + std::to_string(a.bufferView) +
                           " out of range (" + std::to_string(model.bufferViews.size()) +
                           " buffer views)");
    }
    const size_t declared_stride = model.bufferViews[a.bufferView].byteStride;
    if (declared_stride != 0 && (declared_stride < element_size || declared_stride > 252)) {
      return Status::Error(where + ": byteStride " + std::to_string(declared_stride) +
                           " invalid for " + std::to_string(element_size) + "-byte elements");
    }
    const size_t stride = declared_stride != 0 ? declared_stride : element_size;
    const unsigned char* data = nullptr;
    Status status = ViewSpan(model, a.bufferView, a.byteOffset, a.count, element_size, stride,
                             where, &data);
    if (!status.ok()) return status;
    for (size_t e = 0; e < a.count; ++e) {
      for (int c = 0; c < components; ++c) {
        out[e * components + c] =
            ReadComponent(data + e * stride + c * component_size, a.componentType, a.normalized);
      }
    }
  }
  if (a.sparse.isSparse) {
    const size_t sparse_count = static_cast<size_t>(std::max(a.sparse.count, 0));
    if (a.sparse.count < 1 || sparse_count > a.count) {
      return Status::Error(where + ": sparse count " + std::to_string(a.sparse.count) +
                           " not in [1, " + std::to_string(a.count) + "]");
    }
    const int index_type = a.sparse.indices.componentType;
    if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      return Status::Error(where + ": sparse indices component type " + std::to_string(index_type));
    }
    if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0) {
      return Status::Error(where + ": negative sparse byteOffset");
    }
    const size_t index_size =
        static_cast<size_t>(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(index_type)));
    const unsigned char* indices = nullptr;
    const unsigned char* sparse_values = nullptr;
    Status status = ViewSpan(model, a.sparse.indices.bufferView, a.sparse.indices.byteOffset,
                             sparse_count, index_size, index_size, where + ": sparse indices",
                             &indices);
    if (!status.ok()) return status;
    status = ViewSpan(model, a.sparse.values.bufferView, a.sparse.values.byteOffset, sparse_count,
                      element_size, element_size, where + ": sparse values", &sparse_values);
    if (!status.ok()) return status;
    for (size_t k = 0; k < sparse_count; ++k) {
      const double target = ReadComponent(indices + k * index_size, index_type, false);
      if (!(target >= 0.0 && target < static_cast<double>(a.count))) {
        return Status::Error(where + ": sparse index " + std::to_string(target) +
                             " out of range (count " + std::to_string(a.count) + ")");
      }
      const size_t e = static_cast<size_t>(target);
      for (int c = 0; c < components; ++c) {
        out[e * components + c] = ReadComponent(sparse_values + k * element_size + c * component_size,
                                                a.componentType, a.normalized);
      }
    }
  }
  for (size_t k = 0; k < out.size(); ++k) {
    if (!std::isfinite(out[k])) {
      return Status::Error(where + ": element " + std::to_string(k / components) +
                           " is not finite");
    }
  }
  *values = std::move(out);
  *count = a.count;
  return Status::Ok();
}

}  // namespace mocapsolve::gltf_internal

namespace mocapsolve::gltf_internal {

Status BuildRig(const tinygltf::Model& model, const NodeGraph& graph, int skin,
                const std::string& file, Rig* rig) {
  const int num_nodes = static_cast<int>(model.nodes.size());
  const tinygltf::Skin& s = model.skins[skin];
  const std::string where = file + ": skin " + std::to_string(skin);
  if (s.joints.empty()) return Status::Error(where + ": has no joints");
  std::vector<int> skin_index_of_node(num_nodes, -1);
  for (size_t k = 0; k < s.joints.size(); ++k) {
    const int node = s.joints[k];
    if (node < 0 || node >= num_nodes) {
      return Status::Error(where + ": joint " + std::to_string(k) + ": node " +
                           std::to_string(node) + " out of range (" + std::to_string(num_nodes) +
                           " nodes)");
    }
    if (skin_index_of_node[node] != -1) {
      return Status::Error(where + ": joint " + std::to_string(k) + ": node " +
                           std::to_string(node) + " listed twice");
    }
    skin_index_of_node[node] = static_cast<int>(k);
  }
  // Root joints: no joint among their ancestors.
  auto joint_ancestor = [&](int node) {
    for (int a = graph.parent[node]; a != -1; a = graph.parent[a]) {
      if (skin_index_of_node[a] != -1) return a;
    }
    return -1;
  };
  std::vector<int> roots;
  for (int node : s.joints) {
    if (joint_ancestor(node) == -1) roots.push_back(node);
  }
  std::vector<bool> in_rig(num_nodes, false);
  for (int node : s.joints) in_rig[node] = true;
  bool synthetic_root = false;
  if (roots.size() > 1) {
    // Lowest common ancestor of all roots: the deepest node on every root's path.
    auto path_from_top = [&](int node) {
      std::vector<int> path;
      for (int a = node; a != -1; a = graph.parent[a]) path.push_back(a);
      std::reverse(path.begin(), path.end());
      return path;
    };
    std::vector<int> common = path_from_top(roots[0]);
    common.pop_back();  // A root is not its own ancestor's candidate.
    for (size_t r = 1; r < roots.size(); ++r) {
      const std::vector<int> path = path_from_top(roots[r]);
      size_t k = 0;
      while (k < common.size() && k + 1 < path.size() && common[k] == path[k]) ++k;
      common.resize(k);
    }
    if (common.empty()) {
      synthetic_root = true;
    } else {
      in_rig[common.back()] = true;
    }
  }
  // Preorder over the forest (top-level nodes in index order), keeping rig nodes.
  Rig out;
  if (synthetic_root) {
    out.joint_nodes.push_back(-1);
    out.parents.push_back(-1);
    out.chains.emplace_back();
  }
  std::vector<int> joint_of_node(num_nodes, -1);
  std::vector<int> stack;
  for (int top = num_nodes - 1; top >= 0; --top) {
    if (graph.parent[top] == -1) stack.push_back(top);
  }
  // Top-level nodes were pushed in reverse so that node 0's tree comes first.
  while (!stack.empty()) {
    const int node = stack.back();
    stack.pop_back();
    if (in_rig[node]) {
      int parent_node = -1;
      std::vector<int> chain = {node};
      for (int a = graph.parent[node]; a != -1; a = graph.parent[a]) {
        if (in_rig[a]) {
          parent_node = a;
          break;
        }
        chain.push_back(a);
      }
      std::reverse(chain.begin(), chain.end());
      const int parent_joint = parent_node != -1 ? joint_of_node[parent_node]
                               : synthetic_root   ? 0
                                                  : -1;
      joint_of_node[node] = static_cast<int>(out.joint_nodes.size());
      out.joint_nodes.push_back(node);
      out.parents.push_back(parent_joint);
      out.chains.push_back(std::move(chain));
    }
    const std::vector<int>& children = model.nodes[node].children;
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
  }
  out.skin_joints.resize(s.joints.size());
  for (size_t k = 0; k < s.joints.size(); ++k) out.skin_joints[k] = joint_of_node[s.joints[k]];
  // Names: the node's, made unique.
  std::vector<std::string> used;
  for (int node : out.joint_nodes) {
    std::string name = node == -1 ? std::string("gltf_root") : model.nodes[node].name;
    if (name.empty()) name = "node" + std::to_string(node);
    for (char& c : name) {
      if (c == '\n' || c == '\r') c = ' ';
    }
    if (std::find(used.begin(), used.end(), name) != used.end()) {
      name += "#" + std::to_string(node);
    }
    used.push_back(name);
  }
  out.names = std::move(used);
  // Rest rotations: the chain above each joint's node, at the default transforms.
  out.rest_rotations.assign(out.joint_nodes.size(), Eigen::Quaterniond::Identity());
  for (size_t j = 0; j < out.chains.size(); ++j) {
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    for (size_t k = 0; k + 1 < out.chains[j].size(); ++k) q = q * graph.local[out.chains[j][k]].rotation;
    out.rest_rotations[j] = q.normalized();
  }
  Pose rest;
  EvaluateRig(out, graph.local, &rest, &out.rest_scales);
  *rig = std::move(out);
  return Status::Ok();
}

void EvaluateRig(const Rig& rig, const std::vector<Similarity>& locals, Pose* pose,
                 std::vector<double>* scales) {
  const size_t nj = rig.joint_nodes.size();
  pose->translations.resize(nj);
  pose->rotations.resize(nj);
  scales->resize(nj);
  for (size_t j = 0; j < nj; ++j) {
    Similarity c;
    for (int node : rig.chains[j]) c = c * locals[node];
    const double parent_scale = rig.parents[j] >= 0 ? (*scales)[rig.parents[j]] : 1.0;
    (*scales)[j] = parent_scale * c.scale;
    pose->translations[j] = parent_scale * c.translation;
    pose->rotations[j] = (rig.rest_rotations[j].conjugate() * c.rotation).normalized();
  }
}

}  // namespace mocapsolve::gltf_internal
