// Internal to io/ (gltf_reader.cc): the rigid parts of a glTF character. Not installed API.
//
// Game characters often skin only part of their body: RobotExpressive skins its hands and
// carries its head, torso, arms and legs as meshes on nodes parented to bones. A mesh node
// without a skin whose nearest joint above it (in the node graph) is a joint of the rig is
// such a part: each of its vertices becomes a vertex of the character's skinned mesh with
// weight 1 on that joint, placed where the bone carries it in the bind pose:
//     x_bind = X_j (s_j (W_j^-1 W_n v)),   n_bind = R(X_j) R(W_j^-1 W_n) n,
// W the nodes' default world similarities, s_j joint j's accumulated scale at rest (the
// model's joint frames are unscaled), X_j its bind transform (the reader's world_bind). Its triangles
// follow (offset), and their TEXCOORD_0 where the skinned mesh has texture coordinates
// (a part without them leaves the whole mesh without). Primitives that are not triangles,
// or lack NORMAL while the skinned mesh has normals, are skipped (a warning).
#ifndef MOCAPSOLVE_IO_GLTF_RIGID_PARTS_H_
#define MOCAPSOLVE_IO_GLTF_RIGID_PARTS_H_

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "io/gltf_scene.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"

namespace mocapsolve::gltf_internal {

// Appends the rigid parts to spec (rest_positions, rest_normals when it has them, influences)
// and *triangles; *parts: how many mesh nodes were added.
Status AppendRigidParts(const tinygltf::Model& model, const std::string& file, const NodeGraph& graph, const Rig& rig,
                        const std::vector<Eigen::Isometry3d>& world_bind, SkinnedMeshSpec* spec,
                        std::vector<int>* triangles, int* parts, std::vector<std::string>* warnings);

}  // namespace mocapsolve::gltf_internal

#endif  // MOCAPSOLVE_IO_GLTF_RIGID_PARTS_H_
