// Internal to io/ (gltf_reader.cc, gltf_writer.cc): the glTF node graph as uniform-scale
// similarities, and the checked accessor reads. Not installed API.
//
// A node's local transform is the similarity (s, R, t): x -> t + s R x. Composition:
// (s1, R1, t1) * (s2, R2, t2) = (s1 s2, R1 R2, t1 + s1 R1 t2).
#ifndef MOCAPSOLVE_IO_GLTF_SCENE_H_
#define MOCAPSOLVE_IO_GLTF_SCENE_H_

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "io/input_limits.h"
#include "kinematics/motion.h"
#include "kinematics/quote_token.h"
#include "kinematics/status.h"

namespace tinygltf {
class Model;
}

namespace mocapsolve::gltf_internal {

struct Similarity {
  double scale = 1.0;
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Similarity operator*(const Similarity& b) const {
    Similarity c;
    c.scale = scale * b.scale;
    c.rotation = rotation * b.rotation;
    c.translation = translation + scale * (rotation * b.translation);
    return c;
  }
};

// Closest uniform-scale similarity to an affine 4x4 (column-major) matrix: scale =
// cbrt|det|, rotation from the polar decomposition. *exact is false when the linear
// part is not s * rotation to 1e-5 (relative) or the matrix has a projective row.
Similarity SimilarityFromMatrix(const Eigen::Matrix4d& m, bool* exact);

// Checked node graph: every child index in range, one parent per node, no cycle. Local
// default transforms with a uniform scale (approximations reported in *warnings).
struct NodeGraph {
  std::vector<int> parent;          // -1 for a top-level node.
  std::vector<Similarity> local;    // Default TRS / matrix of each node.
  std::vector<Eigen::Vector3d> raw_scale;  // The node's TRS scale (1,1,1 for a matrix).
  std::vector<bool> has_matrix;
};
Status BuildNodeGraph(const tinygltf::Model& model, const std::string& file,
                      NodeGraph* graph, std::vector<std::string>* warnings);

// Uniform scale from a TRS scale; *exact false if non-uniform or not positive.
double UniformScale(const Eigen::Vector3d& scale, bool* exact);

// The key spacing of a clip: the smallest spacing, if every spacing is an integer
// multiple of it (to 1e-3 of it; keys dropped where a curve is linear or constant);
// else 0 (no common key rate).
double KeySpacing(const std::vector<double>& spacings);

// Highest frame rate a glTF or FBX animation is sampled at (io/input_limits.h, the
// BVH reader's 1e-6 s frame time): keys a denormal apart must not become 1e39 fps.
constexpr double kMaxSampleRate = kMaxFrameRate;

using mocapsolve::ShortNumber;  // kinematics/quote_token.h

// Reads accessor `index` as doubles, `components` values per element (1 SCALAR, 3 VEC3,
// 4 VEC4, 16 MAT4), with the given allowed component types (TINYGLTF_COMPONENT_TYPE_*),
// normalized integers mapped per the glTF spec, sparse substitution applied, all bounds
// checked. Errors name "<file>: <field>: accessor N: ...".
Status ReadAccessor(const tinygltf::Model& model, int index, int components,
                    const std::vector<int>& allowed_component_types, const std::string& file,
                    const std::string& field, std::vector<double>* values, size_t* count);

// The skin's joints as a preorder skeleton over the node graph (see gltf_reader.h):
// joint_nodes[j] is the node of joint j (-1 for the synthetic root), chains[j] the nodes
// from below the parent joint's node (the top-level node for a root) down to j's node.
struct Rig {
  std::vector<int> joint_nodes;
  std::vector<int> parents;
  std::vector<std::vector<int>> chains;
  std::vector<int> skin_joints;              // Skeleton joint of each skin.joints entry.
  std::vector<std::string> names;            // Unique joint names.
  QuaternionVector rest_rotations;           // Chain rotation above the joint's node.
  std::vector<double> rest_scales;           // Accumulated uniform scale at rest.
};
Status BuildRig(const tinygltf::Model& model, const NodeGraph& graph, int skin,
                const std::string& file, Rig* rig);

// Pose (translations/rotations per gltf_reader.h) and accumulated scales of the joints
// for node local transforms `locals` (one per node).
void EvaluateRig(const Rig& rig, const std::vector<Similarity>& locals, Pose* pose,
                 std::vector<double>* scales);

}  // namespace mocapsolve::gltf_internal

#endif  // MOCAPSOLVE_IO_GLTF_SCENE_H_
