#include "io/fbx_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>
#include <utility>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/scene.h>

#include "io/atomic_file.h"
#include "io/gltf_scene.h"
#include "io/input_limits.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

using gltf_internal::Rig;
using gltf_internal::Similarity;

// Deepest node hierarchy accepted (real skeletons nest < 40 deep).
constexpr int kMaxFbxDepth = 1000;

// assimp's messages may span lines.
std::string OneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

struct FlatNode {
  const aiNode* node;
  int parent;
};

// Preorder DFS, children in file order, with an explicit stack (the hierarchy's depth
// comes from the file's Connections and must not drive the recursion depth).
Status Flatten(const aiNode* root, const std::string& name, std::vector<FlatNode>* out) {
  std::vector<std::pair<const aiNode*, int>> stack = {{root, -1}};
  std::vector<int> depth_of;
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    const int depth = parent < 0 ? 0 : depth_of[parent] + 1;
    if (depth > kMaxFbxDepth) {
      return Status::Error(name + ": node hierarchy deeper than " + std::to_string(kMaxFbxDepth) +
                           " levels");
    }
    const int index = static_cast<int>(out->size());
    out->push_back({node, parent});
    depth_of.push_back(depth);
    for (unsigned c = node->mNumChildren; c-- > 0;) stack.push_back({node->mChildren[c], index});
  }
  return Status::Ok();
}

// assimp's FBX importer cannot be trusted on hostile input: Debian's build double-frees
// in aiScene::~aiScene on duplicate model names, and recurses once per nesting level of
// the node graph. So it first parses the bytes in a forked child; a child that dies
// (signal, sanitizer abort, the 60 s alarm) becomes a one-line error here. Only bytes
// the child parsed and freed cleanly are parsed again in this process. Exit codes: 0 =
// parsed, kChildParseError = assimp's own error (message on the pipe), else a crash.
constexpr int kChildParseError = 97;
constexpr unsigned kChildSeconds = 60;

void ImportInto(Assimp::Importer* importer, std::string_view bytes, const aiScene** scene,
                std::string* error) {
  importer->SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  importer->SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_ANIMATIONS, true);
  *scene = nullptr;
  try {
    *scene = importer->ReadFileFromMemory(bytes.data(), bytes.size(), 0, "fbx");
  } catch (const std::exception& e) {
    *error = e.what();
    return;
  }
  if (*scene == nullptr || (*scene)->mRootNode == nullptr) {
    *error = importer->GetErrorString();
    if (error->empty()) *error = "cannot read the file";
  }
}

Status AssimpSurvives(std::string_view bytes, const std::string& name) {
  int fds[2];
  if (pipe(fds) != 0) return Status::Error(name + ": pipe: " + std::strerror(errno));
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    return Status::Error(name + ": fork: " + std::strerror(errno));
  }
  if (pid == 0) {  // Child: parse, free, report; _exit skips atexit handlers (and LSan).
    close(fds[0]);
    alarm(kChildSeconds);
    std::string error;
    {
      Assimp::Importer importer;
      const aiScene* scene = nullptr;
      ImportInto(&importer, bytes, &scene, &error);
    }
    if (!error.empty()) {
      size_t done = 0;
      while (done < error.size()) {
        const ssize_t n = write(fds[1], error.data() + done, error.size() - done);
        if (n <= 0) break;
        done += static_cast<size_t>(n);
      }
    }
    _exit(error.empty() ? 0 : kChildParseError);
  }
  close(fds[1]);
  std::string message;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(fds[0], buffer, sizeof(buffer));
    if (n > 0) {
      if (message.size() < 4096) message.append(buffer, static_cast<size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  close(fds[0]);
  int wstatus = 0;
  while (waitpid(pid, &wstatus, 0) < 0) {
    if (errno != EINTR) return Status::Error(name + ": waitpid: " + std::strerror(errno));
  }
  if (WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0) return Status::Ok();
  if (WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == kChildParseError) {
    return Status::Error(name + ": assimp: " + OneLine(message));
  }
  if (WIFSIGNALED(wstatus) && WTERMSIG(wstatus) == SIGALRM) {
    return Status::Error(name + ": assimp did not finish parsing within " +
                         std::to_string(kChildSeconds) + " s");
  }
  const std::string how = WIFSIGNALED(wstatus)
                              ? std::string("signal ") + std::to_string(WTERMSIG(wstatus)) + ", " +
                                    strsignal(WTERMSIG(wstatus))
                              : "exit code " + std::to_string(WEXITSTATUS(wstatus));
  return Status::Error(name + ": assimp crashed parsing the file (" + how + ")");
}

Eigen::Matrix4d ToEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  e << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return e;
}

bool ParseIndex(const std::string& s, int* index) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  *index = std::stoi(s);
  return true;
}

template <typename Key>
size_t KeyAfter(const Key* keys, unsigned n, double ticks) {
  size_t lo = 0, hi = n;  // First key with time > ticks.
  while (lo < hi) {
    const size_t mid = (lo + hi) / 2;
    if (keys[mid].mTime <= ticks) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return lo;
}

Eigen::Vector3d SampleVector(const aiVectorKey* keys, unsigned n, double ticks) {
  auto v = [&](size_t k) { return Eigen::Vector3d(keys[k].mValue.x, keys[k].mValue.y, keys[k].mValue.z); };
  if (n == 1 || ticks <= keys[0].mTime) return v(0);
  if (ticks >= keys[n - 1].mTime) return v(n - 1);
  const size_t k1 = KeyAfter(keys, n, ticks), k0 = k1 - 1;
  const double dt = keys[k1].mTime - keys[k0].mTime;
  const double s = dt > 0 ? (ticks - keys[k0].mTime) / dt : 0.0;
  return (1 - s) * v(k0) + s * v(k1);
}

Eigen::Quaterniond SampleRotation(const aiQuatKey* keys, unsigned n, double ticks) {
  auto q = [&](size_t k) {
    const aiQuaternion& a = keys[k].mValue;
    return Eigen::Quaterniond(a.w, a.x, a.y, a.z).normalized();
  };
  if (n == 1 || ticks <= keys[0].mTime) return q(0);
  if (ticks >= keys[n - 1].mTime) return q(n - 1);
  const size_t k1 = KeyAfter(keys, n, ticks), k0 = k1 - 1;
  const double dt = keys[k1].mTime - keys[k0].mTime;
  const double s = dt > 0 ? (ticks - keys[k0].mTime) / dt : 0.0;
  return q(k0).slerp(s, q(k1)).normalized();
}


// The nodes the meshes' bones name (a skinned mesh's skeleton), in flattened order.
std::vector<int> SkinnedBoneNodes(const aiScene* scene, const std::vector<FlatNode>& nodes) {
  std::map<std::string, int> node_by_name;
  for (int i = static_cast<int>(nodes.size()) - 1; i >= 0; --i) node_by_name[nodes[i].node->mName.C_Str()] = i;
  std::vector<bool> bone(nodes.size(), false);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    for (unsigned b = 0; mesh != nullptr && b < mesh->mNumBones; ++b) {
      const auto it = node_by_name.find(mesh->mBones[b]->mName.C_Str());
      if (it != node_by_name.end()) bone[it->second] = true;
    }
  }
  std::vector<int> out;
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
    if (bone[i]) out.push_back(i);
  }
  return out;
}

// Meshes, vertices and bones, and every mesh instance's vertices in the world (the nodes'
// default transforms, file units).
void CountMeshes(const aiScene* scene, const std::vector<FlatNode>& nodes, FbxInfo* info) {
  std::vector<Eigen::Matrix4d> world(nodes.size());
  long long instanced = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Matrix4d local = ToEigen(nodes[i].node->mTransformation);
    world[i] = nodes[i].parent < 0 ? local : Eigen::Matrix4d(world[nodes[i].parent] * local);
    for (unsigned k = 0; k < nodes[i].node->mNumMeshes; ++k) {
      const unsigned m = nodes[i].node->mMeshes[k];
      if (m < scene->mNumMeshes) instanced += scene->mMeshes[m]->mNumVertices;
    }
  }
  info->meshes = static_cast<int>(scene->mNumMeshes);
  std::set<std::string> bones;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    info->vertices += mesh->mNumVertices;
    if (mesh->mNumBones > 0) ++info->skinned_meshes;
    for (unsigned b = 0; b < mesh->mNumBones; ++b) bones.insert(mesh->mBones[b]->mName.C_Str());
  }
  info->bones = static_cast<int>(bones.size());
  if (!(instanced <= 10000000)) return;  // The count is enough for a huge scene.
  info->mesh_vertices.resize(3, instanced);
  long long v = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    for (unsigned k = 0; k < nodes[i].node->mNumMeshes; ++k) {
      const unsigned m = nodes[i].node->mMeshes[k];
      if (m >= scene->mNumMeshes) continue;
      const aiMesh* mesh = scene->mMeshes[m];
      for (unsigned p = 0; p < mesh->mNumVertices; ++p, ++v) {
        const aiVector3D& x = mesh->mVertices[p];
        info->mesh_vertices.col(v) = (world[i] * Eigen::Vector4d(x.x, x.y, x.z, 1.0)).head<3>();
      }
    }
  }
}

// Rejects, before assimp sees the bytes, a bad frame rate option and an ASCII FBX nested
// deeper than assimp's recursive parser survives.
Status CheckFbxInput(std::string_view bytes, const std::string& path, const FbxReadOptions& options) {
  if (!(options.frame_rate >= 0.0) || !std::isfinite(options.frame_rate)) {
    return Status::Error(path + ": frame rate must be positive (or 0 for the key rate)");
  }
  // assimp's ASCII FBX parser recurses once per brace: bound the depth first.
  constexpr std::string_view kBinaryMagic = "Kaydara FBX Binary";
  if (bytes.substr(0, kBinaryMagic.size()) != kBinaryMagic &&
      FbxBraceDepth(bytes) > kMaxThirdPartyNesting) {
    return Status::Error(path + ": ASCII FBX nested more than " +
                         std::to_string(kMaxThirdPartyNesting) + " braces deep");
  }
  return Status::Ok();
}

// The scene-wide part of FbxInfo (unit scale factor, animation names, mesh counts), read
// before the skeleton so that a file without animation still reports them.
void ReadSceneInfo(const aiScene* scene, const std::vector<FlatNode>& nodes, FbxInfo* info) {
  if (scene->mMetaData != nullptr) {
    double factor = 0.0;
    float factor_f = 0.0f;
    if (scene->mMetaData->Get("UnitScaleFactor", factor) && factor > 0.0 && std::isfinite(factor)) {
      info->unit_scale_factor = factor;
    } else if (scene->mMetaData->Get("UnitScaleFactor", factor_f) && factor_f > 0.0f &&
               std::isfinite(factor_f)) {
      info->unit_scale_factor = factor_f;
    }
  }
  for (unsigned a = 0; a < scene->mNumAnimations; ++a) {
    info->animation_names.push_back(scene->mAnimations[a]->mName.C_Str());
  }
  CountMeshes(scene, nodes, info);
}

// The animation options.animation names (by name first, then by index; 0 when empty), so
// that one clip of a multi-clip file is read; errors list the clips there are.
Status ChooseAnimation(const aiScene* scene, const std::string& path, const FbxReadOptions& options,
                       const std::vector<std::string>& names, int* anim_index) {
  if (scene->mNumAnimations == 0 && !options.skeleton_without_animation) {
    return Status::Error(path + ": has no animation");
  }
  if (scene->mNumAnimations == 0 && !options.animation.empty()) {
    return Status::Error(path + ": animation " + QuoteToken(options.animation) + " not found (the file has none)");
  }
  *anim_index = 0;
  if (options.animation.empty()) return Status::Ok();
  *anim_index = -1;
  std::string listed;
  for (unsigned a = 0; a < scene->mNumAnimations; ++a) {
    if (names[a] == options.animation) *anim_index = static_cast<int>(a);
    listed += (a ? ", " : "") + std::to_string(a) + " " + QuoteToken(names[a]);
  }
  int i = 0;
  if (*anim_index < 0 && ParseIndex(options.animation, &i) && i < static_cast<int>(scene->mNumAnimations)) {
    *anim_index = i;
  }
  if (*anim_index < 0) {
    return Status::Error(path + ": animation " + QuoteToken(options.animation) + " not found (animations: " + listed + ")");
  }
  return Status::Ok();
}

// Every node's default local transform as a similarity (the rig's input), warning where
// the node's matrix is not one exactly (non-uniform scale, shear).
Status NodeLocals(const std::vector<FlatNode>& nodes, const std::string& path, std::vector<Similarity>* locals,
                  std::vector<std::string>* warnings) {
  locals->resize(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    bool exact = true;
    const Eigen::Matrix4d m = ToEigen(nodes[i].node->mTransformation);
    if (!m.allFinite()) return Status::Error(path + ": node " + QuoteToken(nodes[i].node->mName.C_Str()) + ": non-finite transform");
    (*locals)[i] = gltf_internal::SimilarityFromMatrix(m, &exact);
    if (!exact) {
      warnings->push_back(path + ": node '" + std::string(nodes[i].node->mName.C_Str()) +
                          "': transform is not a uniform-scale similarity; approximated");
    }
  }
  return Status::Ok();
}

// Maps the clip's channels to nodes (by name; the first node of that name; -1 and a
// warning for an unknown name) and returns the nodes a channel moves, in flattened order:
// they anchor the skeleton.
std::vector<int> MapChannels(const aiAnimation* anim, const std::vector<FlatNode>& nodes, const std::string& where,
                             std::vector<int>* channel_node, std::vector<std::string>* warnings) {
  const int nn = static_cast<int>(nodes.size());
  const unsigned channels = anim != nullptr ? anim->mNumChannels : 0;
  std::map<std::string, int> node_by_name;
  for (int i = nn - 1; i >= 0; --i) node_by_name[nodes[i].node->mName.C_Str()] = i;
  channel_node->assign(channels, -1);
  std::vector<bool> animated(nn, false);
  for (unsigned c = 0; c < channels; ++c) {
    const aiNodeAnim* ch = anim->mChannels[c];
    auto it = node_by_name.find(ch->mNodeName.C_Str());
    if (it == node_by_name.end()) {
      warnings->push_back(where + ": channel for unknown node '" + std::string(ch->mNodeName.C_Str()) + "' ignored");
      continue;
    }
    (*channel_node)[c] = it->second;
    // Channels whose keys never change (Blender keys the armature object and fixed
    // bones) still apply, but do not make their node a joint of their own.
    bool changes = false;
    for (unsigned k = 1; k < ch->mNumPositionKeys && !changes; ++k) {
      changes = !(ch->mPositionKeys[k].mValue == ch->mPositionKeys[0].mValue);
    }
    for (unsigned k = 1; k < ch->mNumRotationKeys && !changes; ++k) {
      changes = !(ch->mRotationKeys[k].mValue == ch->mRotationKeys[0].mValue);
    }
    if (changes) animated[it->second] = true;
  }
  std::vector<int> animated_nodes;
  for (int i = 0; i < nn; ++i) {
    if (animated[i]) animated_nodes.push_back(i);
  }
  return animated_nodes;
}

// The nodes from the scene root down to `root` (inclusive): the chain baked into a root.
std::vector<int> PathFromTop(const std::vector<FlatNode>& nodes, int root) {
  std::vector<int> p;
  for (int a = root; a != -1; a = nodes[a].parent) p.push_back(a);
  std::reverse(p.begin(), p.end());
  return p;
}

// The path from the scene root to the lowest common ancestor (inclusive) of `anchors`
// (not empty): its last node is the skeleton's root, the others are baked into it.
std::vector<int> CommonAncestry(const std::vector<FlatNode>& nodes, const std::vector<int>& anchors) {
  std::vector<int> common = PathFromTop(nodes, anchors[0]);
  for (size_t k = 1; k < anchors.size(); ++k) {
    const std::vector<int> p = PathFromTop(nodes, anchors[k]);
    size_t n = 0;
    while (n < common.size() && n < p.size() && common[n] == p[n]) ++n;
    common.resize(n);
  }
  return common;
}

// The skeleton's joints among the nodes, and the rig that poses them from node transforms.
struct FbxJoints {
  Rig rig;
  std::vector<bool> is_joint;      // Per node.
  std::vector<int> joint_of_node;  // Per node: its joint, or -1.
};

// The joints: the anchors, every node between one and the root (their lowest common
// ancestor), the root, and the inner nodes without meshes below a joint, in preorder (= flattened order: Flatten is a preorder DFS),
// named uniquely; the root's rest rotation is its ancestors' rotation (baked in).
FbxJoints BuildJoints(const std::vector<FlatNode>& nodes, const std::vector<Similarity>& locals,
                      const std::vector<int>& anchors) {
  const int nn = static_cast<int>(nodes.size());
  const std::vector<int> common = CommonAncestry(nodes, anchors);
  const int root = common.back();  // Non-empty: every path starts at the scene root.
  FbxJoints joints;
  joints.is_joint.assign(nn, false);
  for (int i : anchors) {
    for (int a = i; a != -1; a = nodes[a].parent) {
      if (joints.is_joint[a]) break;
      joints.is_joint[a] = true;
      if (a == root) break;
    }
  }
  joints.is_joint[root] = true;
  // A still chain below a joint (fingers a take leaves at rest get no curves from our
  // writer, nor from Blender's with its default simplify) keeps its inner nodes as joints;
  // its leaves become end sites (BuildSkeleton), and nodes with meshes stay out.
  for (int i = root + 1; i < nn; ++i) {  // Preorder: a parent is decided before its children.
    const aiNode* node = nodes[i].node;
    if (!joints.is_joint[i] && joints.is_joint[nodes[i].parent] && node->mNumChildren > 0 && node->mNumMeshes == 0) {
      joints.is_joint[i] = true;
    }
  }
  Rig& rig = joints.rig;
  joints.joint_of_node.assign(nn, -1);
  for (int i = 0; i < nn; ++i) {
    if (!joints.is_joint[i]) continue;
    joints.joint_of_node[i] = static_cast<int>(rig.joint_nodes.size());
    rig.joint_nodes.push_back(i);
    if (i == root) {
      rig.parents.push_back(-1);
      rig.chains.push_back(common);
    } else {
      rig.parents.push_back(joints.joint_of_node[nodes[i].parent]);
      rig.chains.push_back({i});
    }
    std::string name = nodes[i].node->mName.C_Str();
    if (name.empty()) name = "node" + std::to_string(i);
    if (std::find(rig.names.begin(), rig.names.end(), name) != rig.names.end()) {
      name += "#" + std::to_string(i);
    }
    rig.names.push_back(name);
  }
  rig.rest_rotations.assign(rig.joint_nodes.size(), Eigen::Quaterniond::Identity());
  for (size_t k = 0; k + 1 < common.size(); ++k) {
    rig.rest_rotations[0] = rig.rest_rotations[0] * locals[common[k]].rotation;
  }
  rig.rest_rotations[0].normalize();
  return joints;
}

// The skeleton's unit from FBX UnitScaleFactor (centimetres per file unit), as fbx_reader.h states.
LengthUnit FbxUnit(double unit_scale_factor) {
  if (std::abs(unit_scale_factor - 1.0) < 1e-12) return Centimetres();
  char name[64];
  std::snprintf(name, sizeof name, "fbx unit (%g cm)", unit_scale_factor);
  return {name, unit_scale_factor / 100.0};
}

// The skeleton at the nodes' default transforms (writing the rig's rest scales and the
// rest pose): joint offsets and rest rotations from the rig, an end site for each
// childless non-joint child of a joint.
Status BuildSkeleton(const std::vector<FlatNode>& nodes, const std::vector<Similarity>& locals,
                     double unit_scale_factor, const std::string& path, FbxJoints* joints, Pose* rest,
                     Skeleton* skeleton) {
  Rig& rig = joints->rig;
  gltf_internal::EvaluateRig(rig, locals, rest, &rig.rest_scales);
  const int nj = static_cast<int>(rig.joint_nodes.size());
  std::vector<JointSpec> specs(nj);
  for (int j = 0; j < nj; ++j) {
    specs[j].name = rig.names[j];
    specs[j].parent = rig.parents[j];
    specs[j].offset = rest->translations[j];
    specs[j].rest_rotation = rig.rest_rotations[j];
  }
  std::vector<EndSite> end_sites;
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
    const int p = nodes[i].parent;
    if (joints->is_joint[i] || p < 0 || !joints->is_joint[p] || nodes[i].node->mNumChildren != 0) continue;
    EndSite site;
    site.name = nodes[i].node->mName.C_Str();
    site.parent = joints->joint_of_node[p];
    site.offset = rig.rest_scales[site.parent] * locals[i].translation;
    end_sites.push_back(site);
  }
  Status status = Skeleton::Create(std::move(specs), std::move(end_sites), FbxUnit(unit_scale_factor), skeleton);
  if (!status.ok()) return Status::Error(path + ": " + status.message());
  return Status::Ok();
}

// The span of the clip's key times (ticks) and the spacings between consecutive keys,
// from which the sampling rate follows.
struct KeyTimes {
  double t0 = 0.0, t1 = 0.0;
  bool any = false;
  std::vector<double> spacings;

  // Notes keys[0..n); false unless their times are finite and increasing.
  template <typename Key>
  bool Note(const Key* keys, unsigned n) {
    for (unsigned k = 0; k < n; ++k) {
      const double t = keys[k].mTime;
      if (!std::isfinite(t)) return false;
      t0 = any ? std::min(t0, t) : t;
      t1 = any ? std::max(t1, t) : t;
      any = true;
      if (k > 0) {
        const double d = t - keys[k - 1].mTime;
        if (!(d > 0.0)) return false;
        spacings.push_back(d);
      }
    }
    return true;
  }
};

// Error unless every position key of `ch` is finite and every rotation key has a finite,
// non-zero norm (sampling normalizes them).
Status CheckKeyValues(const aiNodeAnim* ch, const std::string& where) {
  for (unsigned k = 0; k < ch->mNumPositionKeys; ++k) {
    const aiVector3D& v = ch->mPositionKeys[k].mValue;
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      return Status::Error(where + ": node '" + std::string(ch->mNodeName.C_Str()) + "': non-finite position key");
    }
  }
  for (unsigned k = 0; k < ch->mNumRotationKeys; ++k) {
    const aiQuaternion& q = ch->mRotationKeys[k].mValue;
    const double norm = std::sqrt(double(q.w) * q.w + double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z);
    if (!std::isfinite(norm) || !(norm > 1e-6)) {
      return Status::Error(where + ": node '" + std::string(ch->mNodeName.C_Str()) + "': bad rotation key");
    }
  }
  return Status::Ok();
}

// Scale keys are used only when uniform and constant over the clip (then they set the
// node's scale for every frame); otherwise they are ignored with a warning.
void ApplyScaleKeys(const aiNodeAnim* ch, const std::string& where, Similarity* local,
                    std::vector<std::string>* warnings) {
  if (ch->mNumScalingKeys == 0) return;
  bool ok = true;
  double first = 0.0;
  for (unsigned k = 0; k < ch->mNumScalingKeys && ok; ++k) {
    const aiVector3D& s = ch->mScalingKeys[k].mValue;
    bool exact = true;
    const double u = gltf_internal::UniformScale(Eigen::Vector3d(s.x, s.y, s.z), &exact);
    if (k == 0) first = u;
    ok = exact && std::isfinite(u) && std::abs(u - first) <= 1e-5 * first;
  }
  if (ok) {
    local->scale = first;
  } else {
    warnings->push_back(where + ": node '" + std::string(ch->mNodeName.C_Str()) +
                        "': scale keys not uniform and constant; ignored");
  }
}

// Checks the keys of every channel mapped to a node and notes their times; their constant
// scales go into *locals (the frames' base, after the rest pose was taken from them).
Status ReadChannelKeys(const aiAnimation* anim, const std::vector<int>& channel_node, const std::string& where,
                       KeyTimes* times, std::vector<Similarity>* locals, std::vector<std::string>* warnings) {
  for (unsigned c = 0; c < anim->mNumChannels; ++c) {
    if (channel_node[c] < 0) continue;
    const aiNodeAnim* ch = anim->mChannels[c];
    if (!times->Note(ch->mPositionKeys, ch->mNumPositionKeys) ||
        !times->Note(ch->mRotationKeys, ch->mNumRotationKeys)) {
      return Status::Error(where + ": node '" + std::string(ch->mNodeName.C_Str()) +
                           "': key times not finite and increasing");
    }
    if (Status status = CheckKeyValues(ch, where); !status.ok()) return status;
    ApplyScaleKeys(ch, where, &(*locals)[channel_node[c]], warnings);
  }
  return Status::Ok();
}

// The sampling rate: the option's, else the key rate (the keys' spacing, 30 fps when
// none; snapped to an integer within 1e-3), bounded as in gltf_reader.cc.
Status ChooseFrameRate(const FbxReadOptions& options, double ticks_per_second, const std::vector<double>& spacings,
                       const std::string& where, double* rate) {
  *rate = options.frame_rate;
  if (*rate == 0.0) {
    const double spacing = gltf_internal::KeySpacing(spacings);
    *rate = spacing > 0.0 ? ticks_per_second / spacing : 30.0;
    if (std::abs(*rate - std::round(*rate)) < 1e-3) *rate = std::round(*rate);
  }
  if (!(*rate > 0.0 && *rate <= gltf_internal::kMaxSampleRate)) {  // As in gltf_reader.cc.
    return Status::Error(where + ": frame rate " + gltf_internal::ShortNumber(*rate) + " (from " +
                         (options.frame_rate > 0.0 ? "the options" : "the key spacing") +
                         ") is not in (0, 1e6] fps");
  }
  return Status::Ok();
}

// The clip's frames at `rate` from the first key: each mapped channel's node takes its
// keys (lerp/slerp between them, the end keys outside) over `locals`; the rig poses them.
void SampleClip(const aiAnimation* anim, const std::vector<int>& channel_node, const Rig& rig,
                const std::vector<Similarity>& locals, double t0, double ticks_per_second, Motion* out) {
  std::vector<Similarity> frame_locals;
  std::vector<double> scales;
  for (int f = 0; f < static_cast<int>(out->frames.size()); ++f) {
    const double ticks = t0 + f / out->frame_rate * ticks_per_second;
    frame_locals = locals;
    for (unsigned c = 0; c < anim->mNumChannels; ++c) {
      if (channel_node[c] < 0) continue;
      const aiNodeAnim* ch = anim->mChannels[c];
      Similarity& l = frame_locals[channel_node[c]];
      if (ch->mNumPositionKeys > 0) l.translation = SampleVector(ch->mPositionKeys, ch->mNumPositionKeys, ticks);
      if (ch->mNumRotationKeys > 0) l.rotation = SampleRotation(ch->mRotationKeys, ch->mNumRotationKeys, ticks);
    }
    gltf_internal::EvaluateRig(rig, frame_locals, &out->frames[f], &scales);
  }
}

// The clip as a motion of the rig's joints: keys checked, rate chosen, span bounded
// (1e7 joint-frames, as in gltf_reader.cc), frames sampled, rotations sign-continuous.
Status SampleAnimation(const aiAnimation* anim, const std::vector<int>& channel_node, const Rig& rig,
                       const FbxReadOptions& options, const std::string& where, std::vector<Similarity>* locals,
                       std::vector<std::string>* warnings, Motion* out) {
  const double ticks_per_second = anim->mTicksPerSecond > 0.0 ? anim->mTicksPerSecond : 25.0;
  KeyTimes times;
  if (Status status = ReadChannelKeys(anim, channel_node, where, &times, locals, warnings); !status.ok()) {
    return status;
  }
  double rate = 0.0;
  if (Status status = ChooseFrameRate(options, ticks_per_second, times.spacings, where, &rate); !status.ok()) {
    return status;
  }
  const double seconds = (times.t1 - times.t0) / ticks_per_second;
  if (!(seconds * rate * rig.joint_nodes.size() < 1e7)) {  // As in gltf_reader.cc.
    return Status::Error(where + ": over 1e7 joint-frames");
  }
  const int num_frames = static_cast<int>(std::floor(seconds * rate + 1e-6 * rate)) + 1;
  out->frame_rate = rate;
  out->frames.resize(num_frames);
  SampleClip(anim, channel_node, rig, *locals, times.t0, ticks_per_second, out);
  MakeSignContinuous(out);
  return Status::Ok();
}

}  // namespace

Status ParseFbx(std::string_view bytes, const std::string& path, const FbxReadOptions& options,
                Skeleton* skeleton, Motion* motion, FbxInfo* info) {
  if (Status status = CheckFbxInput(bytes, path, options); !status.ok()) return status;
  if (Status status = AssimpSurvives(bytes, path); !status.ok()) return status;
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  std::string error;
  ImportInto(&importer, bytes, &scene, &error);
  if (!error.empty()) return Status::Error(path + ": assimp: " + OneLine(error));
  std::vector<FlatNode> nodes;
  if (Status status = Flatten(scene->mRootNode, path, &nodes); !status.ok()) return status;
  FbxInfo out_info;
  ReadSceneInfo(scene, nodes, &out_info);
  int anim_index = 0;
  Status status = ChooseAnimation(scene, path, options, out_info.animation_names, &anim_index);
  if (!status.ok()) return status;
  const aiAnimation* anim = scene->mNumAnimations > 0 ? scene->mAnimations[anim_index] : nullptr;
  const std::string where = anim != nullptr ? path + ": animation " + std::to_string(anim_index) : path;

  std::vector<Similarity> locals;
  status = NodeLocals(nodes, path, &locals, &out_info.warnings);
  if (!status.ok()) return status;
  std::vector<int> channel_node;
  std::vector<int> anchors = MapChannels(anim, nodes, where, &channel_node, &out_info.warnings);
  if (anim == nullptr) anchors = SkinnedBoneNodes(scene, nodes);  // No animation: the skins' bones.
  if (anchors.empty()) {  // A static clip: every keyed node.
    for (int node : channel_node) {
      if (node >= 0) anchors.push_back(node);
    }
    std::sort(anchors.begin(), anchors.end());
  }
  if (anchors.empty()) {
    return Status::Error(anim != nullptr ? where + ": animates no node"
                                         : path + ": has no animation and no skinned mesh (no skeleton to read)");
  }
  FbxJoints joints = BuildJoints(nodes, locals, anchors);
  Pose rest;
  Skeleton out_skeleton;
  status = BuildSkeleton(nodes, locals, out_info.unit_scale_factor, path, &joints, &rest, &out_skeleton);
  if (!status.ok()) return status;
  out_info.default_pose = rest;

  Motion out;
  if (anim == nullptr) {  // One frame: the nodes' default transforms (the bind pose as stored).
    out.frame_rate = options.frame_rate > 0.0 ? options.frame_rate : 30.0;
    out.frames.push_back(rest);
  } else {
    status = SampleAnimation(anim, channel_node, joints.rig, options, where, &locals, &out_info.warnings, &out);
    if (!status.ok()) return status;
  }
  status = ValidateMotion(out_skeleton, out);
  if (!status.ok()) return Status::Error(where + ": " + status.message());
  *skeleton = std::move(out_skeleton);
  *motion = std::move(out);
  if (info != nullptr) *info = std::move(out_info);
  return Status::Ok();
}

Status ReadFbx(const std::string& path, const FbxReadOptions& options, Skeleton* skeleton,
               Motion* motion, FbxInfo* info) {
  std::string bytes;
  if (Status status = ReadFileToString(path, &bytes); !status.ok()) return status;
  return ParseFbx(bytes, path, options, skeleton, motion, info);
}

}  // namespace mocapsolve

