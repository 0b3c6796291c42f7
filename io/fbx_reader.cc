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

}  // namespace

Status ParseFbx(std::string_view bytes, const std::string& path, const FbxReadOptions& options,
                Skeleton* skeleton, Motion* motion, FbxInfo* info) {
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
  if (Status status = AssimpSurvives(bytes, path); !status.ok()) return status;
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  std::string error;
  ImportInto(&importer, bytes, &scene, &error);
  if (!error.empty()) return Status::Error(path + ": assimp: " + OneLine(error));
  std::vector<FlatNode> nodes;
  if (Status status = Flatten(scene->mRootNode, path, &nodes); !status.ok()) return status;
  FbxInfo out_info;
  if (scene->mMetaData != nullptr) {
    double factor = 0.0;
    float factor_f = 0.0f;
    if (scene->mMetaData->Get("UnitScaleFactor", factor) && factor > 0.0 && std::isfinite(factor)) {
      out_info.unit_scale_factor = factor;
    } else if (scene->mMetaData->Get("UnitScaleFactor", factor_f) && factor_f > 0.0f &&
               std::isfinite(factor_f)) {
      out_info.unit_scale_factor = factor_f;
    }
  }
  for (unsigned a = 0; a < scene->mNumAnimations; ++a) {
    out_info.animation_names.push_back(scene->mAnimations[a]->mName.C_Str());
  }
  CountMeshes(scene, nodes, &out_info);
  if (scene->mNumAnimations == 0 && !options.skeleton_without_animation) {
    return Status::Error(path + ": has no animation");
  }
  if (scene->mNumAnimations == 0 && !options.animation.empty()) {
    return Status::Error(path + ": animation " + QuoteToken(options.animation) + " not found (the file has none)");
  }
  int anim_index = 0;
  if (!options.animation.empty()) {
    anim_index = -1;
    std::string names;
    for (unsigned a = 0; a < scene->mNumAnimations; ++a) {
      if (out_info.animation_names[a] == options.animation) anim_index = static_cast<int>(a);
      names += (a ? ", " : "") + std::to_string(a) + " " + QuoteToken(out_info.animation_names[a]);
    }
    int i = 0;
    if (anim_index < 0 && ParseIndex(options.animation, &i) && i < static_cast<int>(scene->mNumAnimations)) {
      anim_index = i;
    }
    if (anim_index < 0) {
      return Status::Error(path + ": animation " + QuoteToken(options.animation) + " not found (animations: " + names + ")");
    }
  }
  const aiAnimation* anim = scene->mNumAnimations > 0 ? scene->mAnimations[anim_index] : nullptr;
  const unsigned channels = anim != nullptr ? anim->mNumChannels : 0;
  const std::string where = anim != nullptr ? path + ": animation " + std::to_string(anim_index) : path;

  const int nn = static_cast<int>(nodes.size());
  std::vector<Similarity> locals(nn);
  for (int i = 0; i < nn; ++i) {
    bool exact = true;
    const Eigen::Matrix4d m = ToEigen(nodes[i].node->mTransformation);
    if (!m.allFinite()) return Status::Error(path + ": node " + QuoteToken(nodes[i].node->mName.C_Str()) + ": non-finite transform");
    locals[i] = gltf_internal::SimilarityFromMatrix(m, &exact);
    if (!exact) {
      out_info.warnings.push_back(path + ": node '" + std::string(nodes[i].node->mName.C_Str()) +
                                  "': transform is not a uniform-scale similarity; approximated");
    }
  }
  // Channels to nodes (by name; the first node of that name).
  std::map<std::string, int> node_by_name;
  for (int i = nn - 1; i >= 0; --i) node_by_name[nodes[i].node->mName.C_Str()] = i;
  std::vector<int> channel_node(channels, -1);
  std::vector<bool> animated(nn, false);
  for (unsigned c = 0; c < channels; ++c) {
    const aiNodeAnim* ch = anim->mChannels[c];
    auto it = node_by_name.find(ch->mNodeName.C_Str());
    if (it == node_by_name.end()) {
      out_info.warnings.push_back(where + ": channel for unknown node '" +
                                  std::string(ch->mNodeName.C_Str()) + "' ignored");
      continue;
    }
    channel_node[c] = it->second;
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
  if (anim == nullptr) animated_nodes = SkinnedBoneNodes(scene, nodes);  // No animation: the skins' bones.
  if (animated_nodes.empty()) {  // A static clip: every keyed node.
    for (unsigned c = 0; c < channels; ++c) {
      if (channel_node[c] >= 0) animated_nodes.push_back(channel_node[c]);
    }
    std::sort(animated_nodes.begin(), animated_nodes.end());
  }
  if (animated_nodes.empty()) {
    return Status::Error(anim != nullptr ? where + ": animates no node"
                                         : path + ": has no animation and no skinned mesh (no skeleton to read)");
  }
  // Root: lowest common ancestor of the animated nodes (inclusive).
  auto path_from_top = [&](int i) {
    std::vector<int> p;
    for (int a = i; a != -1; a = nodes[a].parent) p.push_back(a);
    std::reverse(p.begin(), p.end());
    return p;
  };
  std::vector<int> common = path_from_top(animated_nodes[0]);
  for (size_t k = 1; k < animated_nodes.size(); ++k) {
    const std::vector<int> p = path_from_top(animated_nodes[k]);
    size_t n = 0;
    while (n < common.size() && n < p.size() && common[n] == p[n]) ++n;
    common.resize(n);
  }
  const int root = common.back();  // Non-empty: every path starts at the scene root.
  std::vector<bool> is_joint(nn, false);
  for (int i : animated_nodes) {
    for (int a = i; a != -1; a = nodes[a].parent) {
      if (is_joint[a]) break;
      is_joint[a] = true;
      if (a == root) break;
    }
  }
  is_joint[root] = true;
  // Preorder = flattened order (Flatten is a preorder DFS).
  Rig rig;
  std::vector<int> joint_of_node(nn, -1);
  std::vector<EndSite> end_sites;
  for (int i = 0; i < nn; ++i) {
    if (!is_joint[i]) continue;
    joint_of_node[i] = static_cast<int>(rig.joint_nodes.size());
    rig.joint_nodes.push_back(i);
    if (i == root) {
      rig.parents.push_back(-1);
      rig.chains.push_back(common);
    } else {
      rig.parents.push_back(joint_of_node[nodes[i].parent]);
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
  Pose rest;
  gltf_internal::EvaluateRig(rig, locals, &rest, &rig.rest_scales);
  out_info.default_pose = rest;
  const int nj = static_cast<int>(rig.joint_nodes.size());
  std::vector<JointSpec> specs(nj);
  for (int j = 0; j < nj; ++j) {
    specs[j].name = rig.names[j];
    specs[j].parent = rig.parents[j];
    specs[j].offset = rest.translations[j];
    specs[j].rest_rotation = rig.rest_rotations[j];
  }
  for (int i = 0; i < nn; ++i) {
    const int p = nodes[i].parent;
    if (is_joint[i] || p < 0 || !is_joint[p] || nodes[i].node->mNumChildren != 0) continue;
    EndSite site;
    site.name = nodes[i].node->mName.C_Str();
    site.parent = joint_of_node[p];
    site.offset = rig.rest_scales[site.parent] * locals[i].translation;
    end_sites.push_back(site);
  }
  LengthUnit unit;
  if (std::abs(out_info.unit_scale_factor - 1.0) < 1e-12) {
    unit = Centimetres();
  } else {
    char name[64];
    std::snprintf(name, sizeof name, "fbx unit (%g cm)", out_info.unit_scale_factor);
    unit = {name, out_info.unit_scale_factor / 100.0};
  }
  Skeleton out_skeleton;
  Status status = Skeleton::Create(std::move(specs), std::move(end_sites), unit, &out_skeleton);
  if (!status.ok()) return Status::Error(path + ": " + status.message());
  if (anim == nullptr) {  // One frame: the nodes' default transforms (the bind pose as stored).
    Motion still;
    still.frame_rate = options.frame_rate > 0.0 ? options.frame_rate : 30.0;
    still.frames.push_back(rest);
    status = ValidateMotion(out_skeleton, still);
    if (!status.ok()) return Status::Error(path + ": " + status.message());
    *skeleton = std::move(out_skeleton);
    *motion = std::move(still);
    if (info != nullptr) *info = std::move(out_info);
    return Status::Ok();
  }

  // Sampling.
  const double ticks_per_second = anim->mTicksPerSecond > 0.0 ? anim->mTicksPerSecond : 25.0;
  double t0 = 0.0, t1 = 0.0;
  bool any = false;
  std::vector<double> spacings;
  auto note_keys = [&](auto* keys, unsigned n) {
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
  };
  std::vector<bool> use_scale(anim->mNumChannels, false);
  for (unsigned c = 0; c < anim->mNumChannels; ++c) {
    if (channel_node[c] < 0) continue;
    const aiNodeAnim* ch = anim->mChannels[c];
    if (!note_keys(ch->mPositionKeys, ch->mNumPositionKeys) ||
        !note_keys(ch->mRotationKeys, ch->mNumRotationKeys)) {
      return Status::Error(where + ": node '" + std::string(ch->mNodeName.C_Str()) +
                           "': key times not finite and increasing");
    }
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
    if (ch->mNumScalingKeys > 0) {
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
        locals[channel_node[c]].scale = first;
        use_scale[c] = true;
      } else {
        out_info.warnings.push_back(where + ": node '" + std::string(ch->mNodeName.C_Str()) +
                                    "': scale keys not uniform and constant; ignored");
      }
    }
  }
  double rate = options.frame_rate;
  if (rate == 0.0) {
    const double spacing = gltf_internal::KeySpacing(spacings);
    rate = spacing > 0.0 ? ticks_per_second / spacing : 30.0;
    if (std::abs(rate - std::round(rate)) < 1e-3) rate = std::round(rate);
  }
  if (!(rate > 0.0 && rate <= gltf_internal::kMaxSampleRate)) {  // As in gltf_reader.cc.
    return Status::Error(where + ": frame rate " + gltf_internal::ShortNumber(rate) + " (from " +
                         (options.frame_rate > 0.0 ? "the options" : "the key spacing") +
                         ") is not in (0, 1e6] fps");
  }
  const double seconds = (t1 - t0) / ticks_per_second;
  if (!(seconds * rate * rig.joint_nodes.size() < 1e7)) {  // As in gltf_reader.cc.
    return Status::Error(where + ": over 1e7 joint-frames");
  }
  const int num_frames = static_cast<int>(std::floor(seconds * rate + 1e-6 * rate)) + 1;
  Motion out;
  out.frame_rate = rate;
  out.frames.resize(num_frames);
  std::vector<Similarity> frame_locals;
  std::vector<double> scales;
  for (int f = 0; f < num_frames; ++f) {
    const double ticks = t0 + f / rate * ticks_per_second;
    frame_locals = locals;
    for (unsigned c = 0; c < anim->mNumChannels; ++c) {
      if (channel_node[c] < 0) continue;
      const aiNodeAnim* ch = anim->mChannels[c];
      Similarity& l = frame_locals[channel_node[c]];
      if (ch->mNumPositionKeys > 0) l.translation = SampleVector(ch->mPositionKeys, ch->mNumPositionKeys, ticks);
      if (ch->mNumRotationKeys > 0) l.rotation = SampleRotation(ch->mRotationKeys, ch->mNumRotationKeys, ticks);
    }
    gltf_internal::EvaluateRig(rig, frame_locals, &out.frames[f], &scales);
  }
  MakeSignContinuous(&out);
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

