#include "io/gltf_rigid_parts.h"

#include <tiny_gltf.h>

namespace mocapsolve::gltf_internal {
namespace {

const std::vector<int> kFloatOnly = {TINYGLTF_COMPONENT_TYPE_FLOAT};
const std::vector<int> kTexcoordTypes = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
const std::vector<int> kIndices = {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT};

Similarity WorldOf(const NodeGraph& graph, int node) {
  Similarity world = graph.local[node];
  for (int p = graph.parent[node]; p >= 0; p = graph.parent[p]) world = graph.local[p] * world;
  return world;
}

Similarity Inverse(const Similarity& a) {
  Similarity b;
  b.scale = 1.0 / a.scale;
  b.rotation = a.rotation.conjugate();
  b.translation = -(b.scale * (b.rotation * a.translation));
  return b;
}

// One primitive of a rigid part: positions (and normals) into the spec, triangles offset.
Status AppendPrimitive(const tinygltf::Model& model, const std::string& file, const std::string& where,
                       const tinygltf::Primitive& prim, const Eigen::Isometry3d& bind_from_node, double scale, int joint,
                       SkinnedMeshSpec* spec, std::vector<int>* triangles, std::vector<std::string>* warnings) {
  auto attribute = [&](const char* name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  const bool with_normals = spec->rest_normals.cols() == spec->rest_positions.cols();
  if ((prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) || attribute("POSITION") < 0 ||
      (with_normals && attribute("NORMAL") < 0)) {
    warnings->push_back(file + ": " + where + ": not TRIANGLES with POSITION and NORMAL; not a rigid part");
    return Status::Ok();
  }
  std::vector<double> pos, nrm, idx;
  size_t count = 0, c = 0;
  Status status = ReadAccessor(model, attribute("POSITION"), 3, kFloatOnly, file, where + ": POSITION", &pos, &count);
  if (status.ok() && with_normals) {
    status = ReadAccessor(model, attribute("NORMAL"), 3, kFloatOnly, file, where + ": NORMAL", &nrm, &c);
    if (status.ok() && c != count) status = Status::Error(file + ": " + where + ": NORMAL and POSITION differ in count");
  }
  if (status.ok() && prim.indices >= 0) {
    status = ReadAccessor(model, prim.indices, 1, kIndices, file, where + ": indices", &idx, &c);
    if (status.ok() && c % 3 != 0) status = Status::Error(file + ": " + where + ": indices not a multiple of 3");
  }
  if (!status.ok()) return status;
  if (prim.indices < 0) {
    if (count % 3 != 0) return Status::Error(file + ": " + where + ": vertices not a multiple of 3");
    for (size_t v = 0; v < count; ++v) idx.push_back(static_cast<double>(v));
  }
  const Eigen::Index base = spec->rest_positions.cols();
  if (base > 0 && spec->texcoords.cols() == base) {  // The mesh so far has UVs: this part's too, or none.
    std::vector<double> uv;
    if (attribute("TEXCOORD_0") >= 0) {
      status = ReadAccessor(model, attribute("TEXCOORD_0"), 2, kTexcoordTypes, file, where + ": TEXCOORD_0", &uv, &c);
      if (!status.ok()) return status;
    }
    if (uv.size() == 2 * count) {
      spec->texcoords.conservativeResize(2, base + static_cast<Eigen::Index>(count));
      for (size_t v = 0; v < count; ++v) spec->texcoords.col(base + v) = Eigen::Vector2d(uv[2 * v], uv[2 * v + 1]);
    } else {
      spec->texcoords.resize(2, 0);
    }
  }
  spec->rest_positions.conservativeResize(3, base + static_cast<Eigen::Index>(count));
  if (with_normals) spec->rest_normals.conservativeResize(3, base + static_cast<Eigen::Index>(count));
  for (size_t v = 0; v < count; ++v) {
    const Eigen::Vector3d p(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
    spec->rest_positions.col(base + v) = bind_from_node * (scale * p);
    if (with_normals) {
      const Eigen::Vector3d n = bind_from_node.linear() * Eigen::Vector3d(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]);
      spec->rest_normals.col(base + v) = n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitY();
    }
    spec->influences.push_back({{joint, 1.0}});
  }
  for (double i : idx) {
    if (i >= static_cast<double>(count)) return Status::Error(file + ": " + where + ": index out of range");
    triangles->push_back(static_cast<int>(base + static_cast<Eigen::Index>(i)));
  }
  return Status::Ok();
}

}  // namespace

Status AppendRigidParts(const tinygltf::Model& model, const std::string& file, const NodeGraph& graph, const Rig& rig,
                        const std::vector<Eigen::Isometry3d>& world_bind, SkinnedMeshSpec* spec,
                        std::vector<int>* triangles, int* parts, std::vector<std::string>* warnings) {
  *parts = 0;
  std::vector<int> joint_of_node(model.nodes.size(), -1);
  for (size_t j = 0; j < rig.joint_nodes.size(); ++j) {
    if (rig.joint_nodes[j] >= 0) joint_of_node[rig.joint_nodes[j]] = static_cast<int>(j);  // -1: the synthetic root.
  }
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const tinygltf::Node& node = model.nodes[n];
    if (node.skin >= 0 || node.mesh < 0 || node.mesh >= static_cast<int>(model.meshes.size())) continue;
    int joint = -1;
    for (int p = graph.parent[n]; p >= 0 && joint < 0; p = graph.parent[p]) joint = joint_of_node[p];
    if (joint < 0) continue;  // Scenery, or a prop not carried by the character.
    // The vertex in the joint node's frame, times its scale: the unscaled joint frame of the model.
    const Similarity joint_from_node = Inverse(WorldOf(graph, rig.joint_nodes[joint])) * WorldOf(graph, static_cast<int>(n));
    const double joint_scale = rig.rest_scales[joint];
    Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
    local.linear() = joint_from_node.rotation.toRotationMatrix();
    local.translation() = joint_scale * joint_from_node.translation;
    const Eigen::Isometry3d bind_from_node = world_bind[joint] * local;
    const double scale = joint_scale * joint_from_node.scale;
    const tinygltf::Mesh& mesh = model.meshes[node.mesh];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string where = "node " + std::to_string(n) + ": mesh " + std::to_string(node.mesh) +
                                ": primitive " + std::to_string(p);
      Status status = AppendPrimitive(model, file, where, mesh.primitives[p], bind_from_node, scale, joint, spec,
                                      triangles, warnings);
      if (!status.ok()) return status;
    }
    ++*parts;
  }
  return Status::Ok();
}

}  // namespace mocapsolve::gltf_internal
