#include "io/gltf_reader.h"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <utility>

#include <tiny_gltf.h>

#include "io/atomic_file.h"
#include "io/gltf_rigid_parts.h"
#include "io/gltf_scene.h"
#include "io/input_limits.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

using gltf_internal::NodeGraph;
using gltf_internal::ReadAccessor;
using gltf_internal::Rig;
using gltf_internal::Similarity;
using gltf_internal::kMaxSampleRate;

// Images are never decoded: their encoded bytes (PNG, JPEG, ... from a buffer view, an
// external file or a data: URI) are kept in Image::image (as_is), so that a writer can
// embed them (gltf_writer.h: SerializeGltfAsGlb).
bool KeepImageBytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                    const unsigned char* bytes, int size, void*) {
  image->as_is = true;
  image->image.assign(bytes, bytes + std::max(size, 0));
  return true;
}

// tinygltf's messages may span lines; keep the first non-empty one.
std::string FirstLine(const std::string& text) {
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(begin, end - begin);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    if (!line.empty()) return line;
    begin = end + 1;
  }
  return "unknown error";
}

bool ParseIndex(const std::string& s, int* index) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  *index = std::stoi(s);
  return true;
}

const std::vector<int> kFloat = {TINYGLTF_COMPONENT_TYPE_FLOAT};
const std::vector<int> kWeightTypes = {TINYGLTF_COMPONENT_TYPE_FLOAT,
                                       TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                       TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
const std::vector<int> kTexcoordTypes = kWeightTypes;  // glTF: float, normalized ubyte or ushort.
const std::vector<int> kJointTypes = {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
const std::vector<int> kIndexTypes = {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT};
const std::vector<int> kRotationTypes = {
    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
    TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
    TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};

Status FindSkin(const tinygltf::Model& model, const std::string& file, const std::string& selector,
                int* skin) {
  if (model.skins.empty()) return Status::Error(file + ": has no skin");
  int index = 0;
  if (selector.empty()) {
    *skin = 0;
    return Status::Ok();
  }
  if (ParseIndex(selector, &index)) {
    if (index >= static_cast<int>(model.skins.size())) {
      return Status::Error(file + ": skin " + selector + " out of range (" +
                           std::to_string(model.skins.size()) + " skins)");
    }
    *skin = index;
    return Status::Ok();
  }
  std::string names;
  for (size_t k = 0; k < model.skins.size(); ++k) {
    if (model.skins[k].name == selector) {
      *skin = static_cast<int>(k);
      return Status::Ok();
    }
    names += (k ? ", '" : "'") + model.skins[k].name + "'";
  }
  return Status::Error(file + ": no skin named " + QuoteToken(selector) + " (skins: " + names + ")");
}

// Per skin joint: inverse(IBM) as (k, Q, p), and IBM itself.
struct BindData {
  std::vector<Eigen::Matrix4d> ibm;
  std::vector<Similarity> bind;  // Similarity approximation of inverse(IBM).
  std::vector<bool> exact;
};

Status ReadBindData(const tinygltf::Model& model, const std::string& file, int skin,
                    BindData* data) {
  const tinygltf::Skin& s = model.skins[skin];
  const size_t nj = s.joints.size();
  const std::string where = file + ": skin " + std::to_string(skin);
  BindData out;
  out.ibm.assign(nj, Eigen::Matrix4d::Identity());
  if (s.inverseBindMatrices >= 0) {
    std::vector<double> values;
    size_t count = 0;
    Status status = ReadAccessor(model, s.inverseBindMatrices, 16, kFloat, file,
                                 "skin " + std::to_string(skin) + ": inverseBindMatrices",
                                 &values, &count);
    if (!status.ok()) return status;
    if (count < nj) {
      return Status::Error(where + ": inverseBindMatrices accessor " +
                           std::to_string(s.inverseBindMatrices) + " has " + std::to_string(count) +
                           " matrices for " + std::to_string(nj) + " joints");
    }
    for (size_t k = 0; k < nj; ++k) {
      for (int e = 0; e < 16; ++e) out.ibm[k](e % 4, e / 4) = values[16 * k + e];
    }
  }
  for (size_t k = 0; k < nj; ++k) {
    const Eigen::Matrix3d a = out.ibm[k].topLeftCorner<3, 3>();
    const double det = a.determinant();
    const double size = a.cwiseAbs().maxCoeff();
    if (!(std::abs(det) > 1e-12 * size * size * size) || !(size > 0.0)) {
      return Status::Error(where + ": joint " + std::to_string(k) +
                           ": inverse bind matrix is singular");
    }
    bool exact = true;
    out.bind.push_back(gltf_internal::SimilarityFromMatrix(out.ibm[k].inverse(), &exact));
    out.exact.push_back(exact);
  }
  *data = std::move(out);
  return Status::Ok();
}

struct Influence {
  int skin_joint;
  double weight;
};

// The triangles of one primitive of `count` vertices, offset by `base`, appended.
Status AppendTriangles(const tinygltf::Model& model, const std::string& file, const std::string& where,
                       const tinygltf::Primitive& prim, size_t count, size_t base, std::vector<int>* triangles) {
  if (prim.indices < 0) {
    if (count % 3 != 0) {
      return Status::Error(file + ": " + where + ": " + std::to_string(count) +
                           " non-indexed vertices is not a multiple of 3");
    }
    for (size_t v = 0; v < count; ++v) triangles->push_back(static_cast<int>(base + v));
    return Status::Ok();
  }
  std::vector<double> idx;
  size_t c = 0;
  Status status = ReadAccessor(model, prim.indices, 1, kIndexTypes, file, where + ": indices", &idx, &c);
  if (!status.ok()) return status;
  if (c % 3 != 0) {
    return Status::Error(file + ": " + where + ": indices count " + std::to_string(c) + " is not a multiple of 3");
  }
  for (double i : idx) {
    if (i >= static_cast<double>(count)) {
      return Status::Error(file + ": " + where + ": index " + std::to_string(static_cast<long long>(i)) +
                           " out of range (" + std::to_string(count) + " vertices)");
    }
    triangles->push_back(static_cast<int>(base + static_cast<size_t>(i)));
  }
  return Status::Ok();
}

// Merges every primitive of the meshes bound to `skin`; *texcoords (TEXCOORD_0) is left
// empty unless every primitive has them, as *normals.
Status ReadMeshes(const tinygltf::Model& model, const std::string& file, int skin,
                  std::vector<Eigen::Vector3d>* positions, std::vector<Eigen::Vector3d>* normals,
                  std::vector<Eigen::Vector2d>* texcoords, std::vector<std::vector<Influence>>* influences,
                  std::vector<int>* triangles, std::vector<std::string>* warnings) {
  const size_t num_skin_joints = model.skins[skin].joints.size();
  std::vector<bool> seen_mesh(model.meshes.size(), false);
  bool all_normals = true, all_texcoords = true;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const tinygltf::Node& node = model.nodes[n];
    if (node.skin != skin || node.mesh < 0) continue;
    if (node.mesh >= static_cast<int>(model.meshes.size())) {
      return Status::Error(file + ": node " + std::to_string(n) + ": mesh " +
                           std::to_string(node.mesh) + " out of range");
    }
    if (seen_mesh[node.mesh]) continue;  // Instances of one skinned mesh coincide.
    seen_mesh[node.mesh] = true;
    const tinygltf::Mesh& mesh = model.meshes[node.mesh];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      const std::string where = "mesh " + std::to_string(node.mesh) + ": primitive " + std::to_string(p);
      if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) {
        warnings->push_back(file + ": " + where + ": mode " + std::to_string(prim.mode) +
                            " is not TRIANGLES; skipped");
        continue;
      }
      auto attribute = [&](const char* name) {
        auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
      };
      if (attribute("POSITION") < 0) {
        return Status::Error(file + ": " + where + ": has no POSITION");
      }
      if (attribute("JOINTS_0") < 0 || attribute("WEIGHTS_0") < 0) {
        return Status::Error(file + ": " + where + ": skinned primitive has no JOINTS_0/WEIGHTS_0");
      }
      std::vector<double> pos, nrm;
      size_t count = 0, c = 0;
      Status status = ReadAccessor(model, attribute("POSITION"), 3, kFloat, file,
                                   where + ": POSITION", &pos, &count);
      if (!status.ok()) return status;
      if (attribute("NORMAL") >= 0) {
        status = ReadAccessor(model, attribute("NORMAL"), 3, kFloat, file, where + ": NORMAL", &nrm, &c);
        if (!status.ok()) return status;
        if (c != count) {
          return Status::Error(file + ": " + where + ": NORMAL has " + std::to_string(c) +
                               " elements, POSITION " + std::to_string(count));
        }
      } else {
        all_normals = false;
      }
      std::vector<double> uv;
      if (attribute("TEXCOORD_0") >= 0 && all_texcoords) {
        status = ReadAccessor(model, attribute("TEXCOORD_0"), 2, kTexcoordTypes, file, where + ": TEXCOORD_0", &uv, &c);
        if (!status.ok()) return status;
        if (c != count) return Status::Error(file + ": " + where + ": TEXCOORD_0 and POSITION differ in count");
      }
      all_texcoords = all_texcoords && !uv.empty();
      const size_t base = positions->size();
      std::vector<std::vector<Influence>> vertex_influences(count);
      for (int set = 0; set < 2; ++set) {
        const std::string joints_name = "JOINTS_" + std::to_string(set);
        const std::string weights_name = "WEIGHTS_" + std::to_string(set);
        const int ja = attribute(joints_name.c_str());
        const int wa = attribute(weights_name.c_str());
        if (ja < 0 && wa < 0) continue;
        if (ja < 0 || wa < 0) {
          return Status::Error(file + ": " + where + ": " + joints_name + " and " + weights_name +
                               " must come together");
        }
        std::vector<double> joints, weights;
        status = ReadAccessor(model, ja, 4, kJointTypes, file, where + ": " + joints_name, &joints, &c);
        if (!status.ok()) return status;
        if (c != count) {
          return Status::Error(file + ": " + where + ": " + joints_name + " has " +
                               std::to_string(c) + " elements, POSITION " + std::to_string(count));
        }
        status = ReadAccessor(model, wa, 4, kWeightTypes, file, where + ": " + weights_name, &weights, &c);
        if (!status.ok()) return status;
        if (c != count) {
          return Status::Error(file + ": " + where + ": " + weights_name + " has " +
                               std::to_string(c) + " elements, POSITION " + std::to_string(count));
        }
        for (size_t v = 0; v < count; ++v) {
          for (int k = 0; k < 4; ++k) {
            const double w = weights[4 * v + k];
            if (w == 0.0) continue;
            if (w < 0.0) {
              return Status::Error(file + ": " + where + ": " + weights_name + ": vertex " +
                                   std::to_string(v) + " has a negative weight");
            }
            const double joint = joints[4 * v + k];
            if (joint >= static_cast<double>(num_skin_joints)) {
              return Status::Error(file + ": " + where + ": " + joints_name + ": vertex " +
                                   std::to_string(v) + ": joint " +
                                   std::to_string(static_cast<long long>(joint)) +
                                   " out of range (skin " + std::to_string(skin) + " has " +
                                   std::to_string(num_skin_joints) + " joints)");
            }
            std::vector<Influence>& list = vertex_influences[v];
            const int j = static_cast<int>(joint);
            auto it = std::find_if(list.begin(), list.end(),
                                   [j](const Influence& i) { return i.skin_joint == j; });
            if (it != list.end()) {
              it->weight += w;
            } else {
              list.push_back({j, w});
            }
          }
        }
      }
      for (size_t v = 0; v < count; ++v) {
        if (vertex_influences[v].empty()) {
          return Status::Error(file + ": " + where + ": vertex " + std::to_string(v) +
                               " has no skin weight");
        }
        positions->emplace_back(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
        normals->push_back(nrm.empty() ? Eigen::Vector3d::Zero()
                                       : Eigen::Vector3d(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]));
        if (all_texcoords) texcoords->emplace_back(uv[2 * v], uv[2 * v + 1]);
        influences->push_back(std::move(vertex_influences[v]));
      }
      status = AppendTriangles(model, file, where, prim, count, base, triangles);
      if (!status.ok()) return status;
    }
  }
  if (!all_normals) normals->clear();
  if (!all_texcoords) texcoords->clear();
  return Status::Ok();
}

// Unit vertex normals (3 x #V) of a triangle list over `positions` (3 x #V): each
// triangle's (b - a) x (c - a) (its normal times twice its area, glTF's counter-clockwise
// winding facing out) summed over the vertices at the same position (so a mesh stored
// per face, as Fox is, gets smooth normals where its faces meet), then normalized; +y
// where the sum vanishes (a vertex on no triangle, degenerate triangles only).
Eigen::Matrix3Xd AreaWeightedNormals(const Eigen::Matrix3Xd& positions, const std::vector<int>& triangles) {
  const Eigen::Index nv = positions.cols();
  std::map<std::array<double, 3>, int> slot_of_position;
  std::vector<int> slot(nv);
  for (Eigen::Index v = 0; v < nv; ++v) {
    const std::array<double, 3> key = {positions(0, v), positions(1, v), positions(2, v)};
    slot[v] = slot_of_position.emplace(key, static_cast<int>(slot_of_position.size())).first->second;
  }
  Eigen::Matrix3Xd sums = Eigen::Matrix3Xd::Zero(3, static_cast<Eigen::Index>(slot_of_position.size()));
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const Eigen::Vector3d a = positions.col(triangles[t]), b = positions.col(triangles[t + 1]),
                          c = positions.col(triangles[t + 2]);
    const Eigen::Vector3d n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) sums.col(slot[triangles[t + k]]) += n;
  }
  Eigen::Matrix3Xd normals(3, nv);
  for (Eigen::Index v = 0; v < nv; ++v) {
    const Eigen::Vector3d n = sums.col(slot[v]);
    const double length = n.norm();
    normals.col(v) = length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::UnitY();
  }
  return normals;
}

}  // namespace

// tinygltf's reader of external buffers and images: through the readers' common open
// path (ReadFileToString), so that a buffer URI naming a FIFO or /dev/zero is refused
// like any other input instead of blocking or reading forever.
// (tinygltf's own FileExists opens the file, which blocks on a FIFO.)
static bool ExternalFileExists(const std::string& path, void*) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

static bool ReadExternalFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  std::string bytes;
  const Status status = ReadFileToString(path, &bytes);
  if (!status.ok()) {
    if (err != nullptr) *err += status.message() + "\n";
    return false;
  }
  out->assign(bytes.begin(), bytes.end());
  return true;
}

Status GltfDocument::Parse(const std::string& bytes, const std::string& name_for_errors,
                           const std::string& base_dir, GltfDocument* document) {
  auto model = std::make_shared<tinygltf::Model>();
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&KeepImageBytes, nullptr);
  loader.SetFsCallbacks({&ExternalFileExists, &tinygltf::ExpandFilePath, &ReadExternalFile,
                         &tinygltf::WriteWholeFile, nullptr});
  std::string err, warn;
  bool ok = false;
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  if (bytes.size() > 0xffffffffu) return Status::Error(name_for_errors + ": file too large");
  if (binary) {  // tinygltf only says "Invalid glTF binary" for a truncated file.
    if (bytes.size() < 12) {
      return Status::Error(name_for_errors + ": GLB: " + std::to_string(bytes.size()) +
                           " bytes, shorter than the 12-byte header");
    }
    uint32_t version = 0;
    std::memcpy(&version, bytes.data() + 4, 4);
    if (version != 2) {  // tinygltf reads any version as glTF 2.
      return Status::Error(name_for_errors + ": GLB: header version " + std::to_string(version) +
                           ", expected 2 (glTF 2.0)");
    }
    uint32_t declared = 0;
    std::memcpy(&declared, bytes.data() + 8, 4);
    if (declared != bytes.size()) {
      return Status::Error(name_for_errors + ": GLB: header declares " + std::to_string(declared) +
                           " bytes, the file has " + std::to_string(bytes.size()) +
                           (declared > bytes.size() ? " (truncated)" : ""));
    }
  }
  // tinygltf recurses once per JSON nesting level (ParseJsonAsValue for `extras`): bound
  // the depth of the JSON text (the GLB's first chunk) before handing it over.
  std::string_view json(bytes);
  if (binary) {
    uint32_t chunk_length = 0;
    if (bytes.size() >= 20) std::memcpy(&chunk_length, bytes.data() + 12, 4);
    json = std::string_view(bytes).substr(std::min<size_t>(20, bytes.size()), chunk_length);
  }
  if (JsonNestingDepth(json) > kMaxThirdPartyNesting) {
    return Status::Error(name_for_errors + ": glTF JSON nested more than " +
                         std::to_string(kMaxThirdPartyNesting) + " levels deep");
  }
  try {
    if (binary) {
      ok = loader.LoadBinaryFromMemory(model.get(), &err, &warn,
                                       reinterpret_cast<const unsigned char*>(bytes.data()),
                                       static_cast<unsigned int>(bytes.size()), base_dir);
    } else {
      ok = loader.LoadASCIIFromString(model.get(), &err, &warn, bytes.data(),
                                      static_cast<unsigned int>(bytes.size()), base_dir);
    }
  } catch (const std::exception& e) {
    return Status::Error(name_for_errors + ": " + FirstLine(e.what()));
  }
  if (!ok) {
    return Status::Error(name_for_errors + ": " +
                         (binary ? "GLB: " : "glTF JSON: ") + FirstLine(err.empty() ? warn : err));
  }
  document->model_ = std::move(model);
  document->name_ = name_for_errors;
  return Status::Ok();
}

Status GltfDocument::Read(const std::string& path, GltfDocument* document) {
  std::string bytes;
  Status status = ReadFileToString(path, &bytes);
  if (!status.ok()) return status;
  const size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash);
  status = Parse(bytes, path, dir, document);
  if (!status.ok()) return status;
  // tinygltf read the external buffers and images itself: they are inputs too.
  for (const tinygltf::Buffer& buffer : document->model().buffers) {
    if (!buffer.uri.empty() && buffer.uri.rfind("data:", 0) != 0) NoteInputFile(dir + "/" + buffer.uri);
  }
  for (const tinygltf::Image& image : document->model().images) {
    if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) NoteInputFile(dir + "/" + image.uri);
  }
  return Status::Ok();
}

namespace {

// The mesh in the bind pose: each vertex (and normal) mapped by every influencing joint,
// rest_positions = sum_b w_b X_b (c_b IBM_b v0) (X_b = world_bind, c_b = rest_scales, per
// skin joint b = skin_joints[k] with inverse bind matrix ibm[k]), normals likewise (unit;
// +Y where they cancel); the influences in skeleton joints.
void BlendRestVertices(const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& normals,
                       const std::vector<std::vector<Influence>>& influences, const std::vector<int>& skin_joints,
                       const std::vector<Eigen::Matrix4d>& ibm, const std::vector<double>& rest_scales,
                       const std::vector<Eigen::Isometry3d>& world_bind, SkinnedMeshSpec* out) {
  std::vector<Eigen::Matrix<double, 3, 4>> position_maps(skin_joints.size());
  std::vector<Eigen::Matrix3d> normal_ibm(skin_joints.size());
  for (size_t k = 0; k < skin_joints.size(); ++k) {
    const int j = skin_joints[k];
    // X_b * (c_b IBM_b) applied to (v0, 1).
    position_maps[k].leftCols<3>() = world_bind[j].linear() * (rest_scales[j] * ibm[k].topLeftCorner<3, 3>());
    position_maps[k].col(3) =
        world_bind[j].linear() * (rest_scales[j] * ibm[k].topRightCorner<3, 1>()) + world_bind[j].translation();
    normal_ibm[k] = ibm[k].topLeftCorner<3, 3>().inverse().transpose();
  }
  SkinnedMeshSpec& spec = *out;
  const int nv = static_cast<int>(positions.size());
  spec.rest_positions.resize(3, nv);
  spec.rest_normals.resize(3, normals.empty() ? 0 : nv);
  spec.influences.resize(nv);
  for (int v = 0; v < nv; ++v) {
    double total = 0.0;
    for (const Influence& inf : influences[v]) total += inf.weight;
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
    for (const Influence& inf : influences[v]) {
      const double w = inf.weight / total;
      p += w * (position_maps[inf.skin_joint] * positions[v].homogeneous());
      if (!normals.empty()) {
        const Eigen::Vector3d local = normal_ibm[inf.skin_joint] * normals[v];
        const double len = local.norm();
        if (len > 0.0) n += w * (world_bind[skin_joints[inf.skin_joint]].linear() * (local / len));
      }
      spec.influences[v].push_back({skin_joints[inf.skin_joint], inf.weight});
    }
    spec.rest_positions.col(v) = p;
    if (!normals.empty()) {
      const double len = n.norm();
      spec.rest_normals.col(v) = len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitY();
    }
  }
}


// The meshes of the file's other skins whose joints are all joints of the rig (RobotExpressive
// binds its left hand to a second skin over the same 43 joints): read and blended into the
// bind pose as skin `skin`'s, rest_positions = sum_b w_b X_b (c_b IBM'_b v0) with that skin's
// own IBM', then appended (vertices, influences, triangles offset; texture coordinates kept
// only if every part has them). Exact when its bind pose is skin `skin`'s (the same armature
// exported twice), approximate otherwise as skin `skin`'s own spread is. A skin with meshes and
// a joint outside the rig is left out with a warning.
Status AppendOtherSkins(const tinygltf::Model& model, const std::string& file, int skin, const Rig& rig,
                        const std::vector<double>& rest_scales, const std::vector<Eigen::Isometry3d>& world_bind,
                        SkinnedMeshSpec* spec, std::vector<int>* triangles, bool* has_normals,
                        std::vector<std::string>* warnings) {
  std::vector<int> joint_of_node(model.nodes.size(), -1);
  for (size_t j = 0; j < rig.joint_nodes.size(); ++j) {
    if (rig.joint_nodes[j] >= 0) joint_of_node[rig.joint_nodes[j]] = static_cast<int>(j);
  }
  for (int other = 0; other < static_cast<int>(model.skins.size()); ++other) {
    if (other == skin) continue;
    const tinygltf::Skin& s = model.skins[other];
    std::vector<int> skin_joints;
    for (int node : s.joints) {
      const int j = node >= 0 && node < static_cast<int>(model.nodes.size()) ? joint_of_node[node] : -1;
      if (j < 0) break;
      skin_joints.push_back(j);
    }
    bool has_mesh = false;
    for (const tinygltf::Node& node : model.nodes) has_mesh = has_mesh || (node.skin == other && node.mesh >= 0);
    if (!has_mesh) continue;
    if (skin_joints.size() != s.joints.size() || s.joints.empty()) {
      warnings->push_back(file + ": skin " + std::to_string(other) + " has joints outside skin " +
                          std::to_string(skin) + "'s skeleton; its meshes are left out");
      continue;
    }
    std::vector<Eigen::Vector3d> positions, normals;
    std::vector<Eigen::Vector2d> texcoords;
    std::vector<std::vector<Influence>> influences;
    std::vector<int> other_triangles;
    Status status = ReadMeshes(model, file, other, &positions, &normals, &texcoords, &influences, &other_triangles,
                               warnings);
    if (!status.ok()) return status;
    if (positions.empty()) continue;
    BindData bind;
    status = ReadBindData(model, file, other, &bind);
    if (!status.ok()) return status;
    SkinnedMeshSpec part;
    BlendRestVertices(positions, normals, influences, skin_joints, bind.ibm, rest_scales, world_bind, &part);
    const Eigen::Index before = spec->rest_positions.cols(), added = part.rest_positions.cols();
    for (int t : other_triangles) triangles->push_back(static_cast<int>(before) + t);
    spec->rest_positions.conservativeResize(3, before + added);
    spec->rest_positions.rightCols(added) = part.rest_positions;
    *has_normals = *has_normals && !normals.empty();
    if (*has_normals) {
      spec->rest_normals.conservativeResize(3, before + added);
      spec->rest_normals.rightCols(added) = part.rest_normals;
    } else {
      spec->rest_normals.resize(3, 0);
    }
    if (spec->texcoords.cols() == before && static_cast<Eigen::Index>(texcoords.size()) == added) {
      spec->texcoords.conservativeResize(2, before + added);
      for (Eigen::Index v = 0; v < added; ++v) spec->texcoords.col(before + v) = texcoords[v];
    } else {
      spec->texcoords.resize(2, 0);
    }
    for (auto& influence : part.influences) spec->influences.push_back(std::move(influence));
    warnings->push_back(file + ": skin " + std::to_string(other) + "'s meshes (" + std::to_string(added) +
                        " vertices) are bound to skin " + std::to_string(skin) + "'s joints and read with them");
  }
  return Status::Ok();
}
}  // namespace

Status ReadGltfCharacter(const GltfDocument& document, const GltfReadOptions& options,
                         GltfCharacter* character) {
  if (!document.loaded()) return Status::Error("glTF document not loaded");
  const tinygltf::Model& model = document.model();
  const std::string& file = document.name();
  for (const std::string& extension : model.extensionsRequired) {
    if (extension == "KHR_draco_mesh_compression" || extension == "EXT_meshopt_compression" ||
        extension == "KHR_mesh_quantization") {
      return Status::Error(file + ": requires extension " + extension + ", which is not supported");
    }
  }
  GltfCharacter out;
  Status status = FindSkin(model, file, options.skin, &out.skin);
  if (!status.ok()) return status;
  NodeGraph graph;
  status = gltf_internal::BuildNodeGraph(model, file, &graph, &out.warnings);
  if (!status.ok()) return status;
  Rig rig;
  status = gltf_internal::BuildRig(model, graph, out.skin, file, &rig);
  if (!status.ok()) return status;
  const int nj = static_cast<int>(rig.joint_nodes.size());

  // Skeleton: offsets and rest rotations from the default node transforms.
  std::vector<double> rest_scales;
  gltf_internal::EvaluateRig(rig, graph.local, &out.rest_pose, &rest_scales);
  std::vector<JointSpec> specs(nj);
  for (int j = 0; j < nj; ++j) {
    specs[j].name = rig.names[j];
    specs[j].parent = rig.parents[j];
    specs[j].offset = out.rest_pose.translations[j];
    specs[j].rest_rotation = rig.rest_rotations[j];
  }
  status = Skeleton::Create(std::move(specs), {}, Metres(), &out.skeleton);
  if (!status.ok()) return Status::Error(file + ": skin " + std::to_string(out.skin) + ": " + status.message());

  // Bind pose: world_from_joint = [Q_b | r p_b] for skin joints.
  BindData bind;
  status = ReadBindData(model, file, out.skin, &bind);
  if (!status.ok()) return status;
  const size_t num_skin = bind.bind.size();
  std::vector<double> ratios;
  bool all_exact = true;
  for (size_t k = 0; k < num_skin; ++k) {
    ratios.push_back(rest_scales[rig.skin_joints[k]] / bind.bind[k].scale);
    all_exact = all_exact && bind.exact[k];
  }
  std::vector<double> sorted = ratios;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double r = sorted[sorted.size() / 2];
  out.bind_scale = r;
  double spread = 0.0;
  for (double x : ratios) spread = std::max(spread, std::abs(x / r - 1.0));
  if (spread > 1e-4) {
    out.warnings.push_back(file + ": skin " + std::to_string(out.skin) +
                           ": node scales / inverse-bind scales vary by " + std::to_string(spread) +
                           " relative; skinning is approximate");
  }
  if (!all_exact) {
    out.warnings.push_back(file + ": skin " + std::to_string(out.skin) +
                           ": an inverse bind matrix is not a uniform-scale similarity; approximated");
  }
  FkData rest_fk(out.skeleton);
  ForwardKinematics(out.skeleton, out.rest_pose, &rest_fk);
  std::vector<Eigen::Isometry3d> world_bind(nj);
  for (int j = 0; j < nj; ++j) {
    world_bind[j] = Eigen::Isometry3d::Identity();
    world_bind[j].linear() = rest_fk.world_rotations[j].toRotationMatrix();
    world_bind[j].translation() = r * rest_fk.world_positions[j];
  }
  for (size_t k = 0; k < num_skin; ++k) {
    Eigen::Isometry3d x = Eigen::Isometry3d::Identity();
    x.linear() = bind.bind[k].rotation.toRotationMatrix();
    x.translation() = r * bind.bind[k].translation;
    world_bind[rig.skin_joints[k]] = x;
  }
  out.bind_pose.translations.resize(nj);
  out.bind_pose.rotations.resize(nj);
  for (int j = 0; j < nj; ++j) {
    const int p = rig.parents[j];
    const Eigen::Quaterniond world_q(world_bind[j].linear());
    if (p < 0) {
      out.bind_pose.translations[j] = world_bind[j].translation();
      out.bind_pose.rotations[j] = (rig.rest_rotations[j].conjugate() * world_q).normalized();
    } else {
      const Eigen::Quaterniond parent_q(world_bind[p].linear());
      out.bind_pose.translations[j] =
          world_bind[p].linear().transpose() * (world_bind[j].translation() - world_bind[p].translation());
      out.bind_pose.rotations[j] =
          (rig.rest_rotations[j].conjugate() * parent_q.conjugate() * world_q).normalized();
    }
  }

  // Mesh: rest_positions = sum_b w_b X_b (c_b IBM_b v0); normals likewise.
  std::vector<Eigen::Vector3d> positions, normals;
  std::vector<Eigen::Vector2d> texcoords;
  std::vector<std::vector<Influence>> influences;
  std::vector<int> triangles;
  status = ReadMeshes(model, file, out.skin, &positions, &normals, &texcoords, &influences, &triangles,
                      &out.warnings);
  if (!status.ok()) return status;
  SkinnedMeshSpec spec;
  BlendRestVertices(positions, normals, influences, rig.skin_joints, bind.ibm, rest_scales, world_bind, &spec);
  spec.texcoords.resize(2, static_cast<Eigen::Index>(texcoords.size()));
  for (size_t v = 0; v < texcoords.size(); ++v) spec.texcoords.col(static_cast<Eigen::Index>(v)) = texcoords[v];
  bool has_normals = !normals.empty();
  if (options.skin.empty()) {  // The character: every skin over its joints. A chosen skin: that one.
    status = AppendOtherSkins(model, file, out.skin, rig, rest_scales, world_bind, &spec, &triangles, &has_normals,
                              &out.warnings);
    if (!status.ok()) return status;
  }
  int rigid_parts = 0;
  status = gltf_internal::AppendRigidParts(model, file, graph, rig, world_bind, &spec, &triangles, &rigid_parts,
                                           &out.warnings);
  if (!status.ok()) return status;
  if (rigid_parts > 0) {
    out.warnings.push_back(file + ": skin " + std::to_string(out.skin) + ": " + std::to_string(rigid_parts) +
                           " mesh nodes parented to its bones are rigid parts of the character (weight 1 on the bone)");
  }
  if (!has_normals && !triangles.empty()) {
    spec.rest_normals = AreaWeightedNormals(spec.rest_positions, triangles);
    out.warnings.push_back(file + ": skin " + std::to_string(out.skin) +
                           ": the mesh has no normals; area-weighted vertex normals computed from its triangles");
  }
  spec.joint_from_bind.resize(nj);
  for (int j = 0; j < nj; ++j) spec.joint_from_bind[j] = world_bind[j].inverse();
  status = SkinnedMesh::Create(out.skeleton, std::move(spec), &out.mesh);
  if (!status.ok()) return Status::Error(file + ": " + status.message());
  out.triangles.resize(3, static_cast<Eigen::Index>(triangles.size() / 3));
  for (size_t t = 0; t < triangles.size(); ++t) out.triangles(t % 3, t / 3) = triangles[t];

  for (const tinygltf::Animation& a : model.animations) out.animation_names.push_back(a.name);
  out.joint_nodes = rig.joint_nodes;
  out.skin_joints = rig.skin_joints;
  *character = std::move(out);
  return Status::Ok();
}

Status ReadGltfCharacter(const std::string& path, const GltfReadOptions& options,
                         GltfCharacter* character) {
  GltfDocument document;
  Status status = GltfDocument::Read(path, &document);
  if (!status.ok()) return status;
  return ReadGltfCharacter(document, options, character);
}

Status FindGltfAnimation(const GltfDocument& document, const std::string& selector, int* index) {
  const tinygltf::Model& model = document.model();
  const std::string& file = document.name();
  if (model.animations.empty()) return Status::Error(file + ": has no animation");
  int i = 0;
  if (selector.empty()) {
    *index = 0;
    return Status::Ok();
  }
  std::string names;
  for (size_t k = 0; k < model.animations.size(); ++k) {
    if (model.animations[k].name == selector) {
      *index = static_cast<int>(k);
      return Status::Ok();
    }
    names += (k ? ", " : "") + std::to_string(k) + " " + QuoteToken(model.animations[k].name);
  }
  if (ParseIndex(selector, &i)) {
    if (i < static_cast<int>(model.animations.size())) {
      *index = i;
      return Status::Ok();
    }
  }
  return Status::Error(file + ": no animation " + QuoteToken(selector) + " (animations: " + names + ")");
}

namespace {

enum class Path { kTranslation, kRotation, kScale };
enum class Interpolation { kStep, kLinear, kCubic };

struct Track {
  int node;
  Path path;
  Interpolation interpolation;
  int components;                 // 3 or 4.
  std::vector<double> times;
  std::vector<double> values;     // count (x3 for cubic) x components.
};

// Value of a track at time t, `components` numbers into *out.
void SampleTrack(const Track& track, double t, double* out) {
  const int c = track.components;
  const size_t n = track.times.size();
  const bool cubic = track.interpolation == Interpolation::kCubic;
  auto value = [&](size_t k, int part) {  // part: 0 in-tangent, 1 value, 2 out-tangent.
    return cubic ? &track.values[(3 * k + part) * c] : &track.values[k * c];
  };
  if (n == 1 || t <= track.times[0]) {
    std::copy(value(0, 1), value(0, 1) + c, out);
    return;
  }
  if (t >= track.times[n - 1]) {
    std::copy(value(n - 1, 1), value(n - 1, 1) + c, out);
    return;
  }
  const size_t k1 = static_cast<size_t>(
      std::upper_bound(track.times.begin(), track.times.end(), t) - track.times.begin());
  const size_t k0 = k1 - 1;
  const double dt = track.times[k1] - track.times[k0];
  double s = dt > 0.0 ? (t - track.times[k0]) / dt : 0.0;
  // A sample within 1e-5 of the interval from a key takes the key: key times are floats
  // (k / fps rounded), sample times are doubles.
  if (s < 1e-5) s = 0.0;
  if (s > 1.0 - 1e-5) s = 1.0;
  switch (track.interpolation) {
    case Interpolation::kStep:
      std::copy(value(s == 1.0 ? k1 : k0, 1), value(s == 1.0 ? k1 : k0, 1) + c, out);
      break;
    case Interpolation::kLinear:
      if (track.path == Path::kRotation) {
        const double* a = value(k0, 1);
        const double* b = value(k1, 1);
        const Eigen::Quaterniond qa(a[3], a[0], a[1], a[2]), qb(b[3], b[0], b[1], b[2]);
        const Eigen::Quaterniond q = qa.normalized().slerp(s, qb.normalized());
        out[0] = q.x();
        out[1] = q.y();
        out[2] = q.z();
        out[3] = q.w();
      } else {
        for (int i = 0; i < c; ++i) out[i] = (1.0 - s) * value(k0, 1)[i] + s * value(k1, 1)[i];
      }
      break;
    case Interpolation::kCubic: {
      const double s2 = s * s, s3 = s2 * s;
      const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
      const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
      for (int i = 0; i < c; ++i) {
        out[i] = h00 * value(k0, 1)[i] + h10 * dt * value(k0, 2)[i] + h01 * value(k1, 1)[i] +
                 h11 * dt * value(k1, 0)[i];
      }
      break;
    }
  }
}

// Channel `ci` of animation `index` as a track to sample (*kept). Not kept: morph weights,
// nodes outside the rig, and scales; a uniform scale constant over the clip goes into
// `graph` instead, any other scale is ignored with a note.
Status ReadChannelTrack(const tinygltf::Model& model, const std::string& file, int index, size_t ci,
                        const std::vector<bool>& relevant, NodeGraph* graph, std::vector<std::string>* notes,
                        Track* track_out, bool* kept) {
  *kept = false;
  const tinygltf::Animation& anim = model.animations[index];
  const std::string where = file + ": animation " + std::to_string(index);
  const tinygltf::AnimationChannel& ch = anim.channels[ci];
  const std::string cw = where + ": channel " + std::to_string(ci);
  if (ch.target_node < 0 || ch.target_node >= static_cast<int>(model.nodes.size())) {
    return Status::Error(cw + ": target node " + std::to_string(ch.target_node) + " out of range");
  }
  if (ch.sampler < 0 || ch.sampler >= static_cast<int>(anim.samplers.size())) {
    return Status::Error(cw + ": sampler " + std::to_string(ch.sampler) + " out of range");
  }
  Track track;
  track.node = ch.target_node;
  if (ch.target_path == "translation") {
    track.path = Path::kTranslation;
    track.components = 3;
  } else if (ch.target_path == "rotation") {
    track.path = Path::kRotation;
    track.components = 4;
  } else if (ch.target_path == "scale") {
    track.path = Path::kScale;
    track.components = 3;
  } else if (ch.target_path == "weights") {
    return Status::Ok();  // Morph target weights: not skeletal.
  } else {
    return Status::Error(cw + ": unknown target path " + QuoteToken(ch.target_path));
  }
  if (!relevant[ch.target_node]) return Status::Ok();
  const tinygltf::AnimationSampler& sampler = anim.samplers[ch.sampler];
  const std::string sw = "animation " + std::to_string(index) + ": sampler " + std::to_string(ch.sampler);
  if (sampler.interpolation == "STEP") {
    track.interpolation = Interpolation::kStep;
  } else if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty()) {
    track.interpolation = Interpolation::kLinear;
  } else if (sampler.interpolation == "CUBICSPLINE") {
    track.interpolation = Interpolation::kCubic;
  } else {
    return Status::Error(file + ": " + sw + ": unknown interpolation " + QuoteToken(sampler.interpolation));
  }
  size_t num_keys = 0, num_values = 0;
  Status status = ReadAccessor(model, sampler.input, 1, kFloat, file, sw + ": input", &track.times, &num_keys);
  if (!status.ok()) return status;
  status = ReadAccessor(model, sampler.output, track.components,
                        track.path == Path::kRotation ? kRotationTypes : kFloat, file,
                        sw + ": output", &track.values, &num_values);
  if (!status.ok()) return status;
  if (num_keys == 0) return Status::Error(file + ": " + sw + ": input has no keys");
  for (size_t k = 1; k < num_keys; ++k) {
    if (!(track.times[k] > track.times[k - 1])) {
      return Status::Error(file + ": " + sw + ": input times not increasing at key " + std::to_string(k));
    }
  }
  const size_t expected = num_keys * (track.interpolation == Interpolation::kCubic ? 3 : 1);
  if (num_values != expected) {
    return Status::Error(file + ": " + sw + ": output has " + std::to_string(num_values) +
                         " elements, expected " + std::to_string(expected));
  }
  if (track.path == Path::kRotation) {
    for (size_t k = 0; k < expected; ++k) {
      const Eigen::Map<const Eigen::Vector4d> q(&track.values[4 * k]);
      const bool tangent = track.interpolation == Interpolation::kCubic && k % 3 != 1;
      if (!tangent && !(q.norm() > 1e-6)) {
        return Status::Error(file + ": " + sw + ": output " + std::to_string(k) + " is a zero quaternion");
      }
    }
  }
  if (track.path == Path::kScale) {
    // Used only if uniform and constant over the clip (values and zero tangents).
    bool ok = true;
    double first = 0.0;
    for (size_t k = 0; k < num_keys && ok; ++k) {
      const size_t e = track.interpolation == Interpolation::kCubic ? 3 * k + 1 : k;
      const Eigen::Vector3d s(track.values[3 * e], track.values[3 * e + 1], track.values[3 * e + 2]);
      bool exact = true;
      const double u = gltf_internal::UniformScale(s, &exact);
      if (k == 0) first = u;
      ok = exact && std::abs(u - first) <= 1e-5 * first;
      if (track.interpolation == Interpolation::kCubic) {
        for (int i = 0; i < 3; ++i) {
          ok = ok && track.values[3 * (3 * k) + i] == 0.0 && track.values[3 * (3 * k + 2) + i] == 0.0;
        }
      }
    }
    if (!ok) {
      notes->push_back(where + ": channel " + std::to_string(ci) + ": scale of node " +
                       std::to_string(ch.target_node) +
                       " is not uniform and constant; ignored (node default kept)");
      return Status::Ok();
    }
    graph->local[track.node].scale = first;
    return Status::Ok();
  }
  *kept = true;
  *track_out = std::move(track);
  return Status::Ok();
}

}  // namespace

Status ReadGltfAnimation(const GltfDocument& document, const GltfCharacter& character,
                         const GltfAnimationOptions& options, Motion* motion,
                         std::vector<std::string>* warnings) {
  if (!document.loaded()) return Status::Error("glTF document not loaded");
  const tinygltf::Model& model = document.model();
  const std::string& file = document.name();
  if (!(options.frame_rate >= 0.0) || !std::isfinite(options.frame_rate)) {
    return Status::Error(file + ": frame rate must be positive (or 0 for the key rate)");
  }
  int index = 0;
  Status status = FindGltfAnimation(document, options.animation, &index);
  if (!status.ok()) return status;
  const tinygltf::Animation& anim = model.animations[index];
  const std::string where = file + ": animation " + std::to_string(index);
  NodeGraph graph;
  std::vector<std::string> ignored_warnings;
  status = gltf_internal::BuildNodeGraph(model, file, &graph, &ignored_warnings);
  if (!status.ok()) return status;
  Rig rig;
  status = gltf_internal::BuildRig(model, graph, character.skin, file, &rig);
  if (!status.ok()) return status;
  if (rig.joint_nodes != character.joint_nodes ||
      static_cast<int>(rig.joint_nodes.size()) != character.skeleton.num_joints()) {
    return Status::Error(where + ": the character was not read from this file");
  }
  std::vector<bool> relevant(model.nodes.size(), false);
  for (const std::vector<int>& chain : rig.chains) {
    for (int node : chain) relevant[node] = true;
  }
  std::vector<Track> tracks;
  std::vector<std::string> notes;
  for (size_t ci = 0; ci < anim.channels.size(); ++ci) {
    Track track;
    bool kept = false;
    status = ReadChannelTrack(model, file, index, ci, relevant, &graph, &notes, &track, &kept);
    if (!status.ok()) return status;
    if (kept) tracks.push_back(std::move(track));
  }
  // Time range and frame rate.
  double t0 = 0.0, t1 = 0.0;
  bool any = false;
  for (const Track& t : tracks) {
    t0 = any ? std::min(t0, t.times.front()) : t.times.front();
    t1 = any ? std::max(t1, t.times.back()) : t.times.back();
    any = true;
  }
  double rate = options.frame_rate;
  size_t uniform_keys = 0;  // Keys of a track keyed on every step from t0 to t1 (0: none).
  if (rate == 0.0) {
    std::vector<double> spacings;
    for (const Track& t : tracks) {
      for (size_t k = 1; k < t.times.size(); ++k) spacings.push_back(t.times[k] - t.times[k - 1]);
    }
    const double spacing = gltf_internal::KeySpacing(spacings);
    rate = spacing > 0.0 ? 1.0 / spacing : 30.0;
    // The smallest float spacing overstates the rate (a 2,752-key 120 fps clip's keys give
    // 120.016 fps, and late frames drift): a track keyed on every step gives it exactly, its
    // whole span over its number of steps (to the float's error over the span).
    for (const Track& t : tracks) {
      const double span = t.times.back() - t.times.front();
      const size_t n = t.times.size();
      // Keyed on every step: the mean step is the spacing (within KeySpacing's 1e-3).
      if (spacing > 0.0 && n > uniform_keys && n >= 3 &&
          std::abs(span / double(n - 1) - spacing) < 1e-3 * spacing) {
        rate = double(n - 1) / span;
        uniform_keys = t.times.front() == t0 && t.times.back() == t1 ? n : 0;
      }
    }
    // Float key times carry a relative error of ~6e-8: a 1 MHz clip's keys give
    // 1000000.0025 fps, which is 1e6 (and within kMaxSampleRate).
    if (std::abs(rate - std::round(rate)) < std::max(1e-3, 1e-7 * rate)) rate = std::round(rate);
  }
  // Key times 1e-39 s apart would give 1e39 fps (and no int frame count).
  if (!(rate > 0.0 && rate <= kMaxSampleRate)) {
    return Status::Error(where + ": frame rate " + ShortNumber(rate) + " (from " +
                         (options.frame_rate > 0.0 ? "the options" : "the key spacing") +
                         ") is not in (0, 1e6] fps");
  }
  const double span_frames = (t1 - t0) * rate;
  // At most 1e7 joint-frames (about 0.6 GB of poses; a 10-minute 120 fps take of 65
  // joints is 4.7e6).
  if (!(span_frames * character.skeleton.num_joints() < 1e7)) {
    return Status::Error(where + ": " + std::to_string(t1 - t0) + " s at " + std::to_string(rate) +
                         " fps for " + std::to_string(character.skeleton.num_joints()) +
                         " joints is over 1e7 joint-frames");
  }
  // A track keyed on every frame of the whole span sets the count: a clip keyed at 120.0005
  // fps (a BVH's rounded frame time) and read at 120 keeps its last frame.
  const int num_frames = uniform_keys > 0 ? static_cast<int>(uniform_keys)
                                          : static_cast<int>(std::floor(span_frames + 1e-6 * rate)) + 1;
  Motion out;
  out.frame_rate = rate;
  out.frames.resize(num_frames);
  std::vector<Similarity> locals;
  std::vector<double> scales;
  double sample[4];
  for (int f = 0; f < num_frames; ++f) {
    const double t = t0 + f / rate;
    locals = graph.local;
    for (const Track& track : tracks) {
      SampleTrack(track, t, sample);
      Similarity& l = locals[track.node];
      if (track.path == Path::kTranslation) {
        l.translation = Eigen::Vector3d(sample[0], sample[1], sample[2]);
      } else {
        const Eigen::Quaterniond q(sample[3], sample[0], sample[1], sample[2]);
        const double norm = q.norm();
        l.rotation = norm > 1e-12 ? Eigen::Quaterniond(q.coeffs() / norm) : Eigen::Quaterniond::Identity();
      }
    }
    gltf_internal::EvaluateRig(rig, locals, &out.frames[f], &scales);
  }
  MakeSignContinuous(&out);
  status = ValidateMotion(character.skeleton, out);
  if (!status.ok()) return Status::Error(where + ": " + status.message());
  *motion = std::move(out);
  if (warnings != nullptr) *warnings = std::move(notes);
  return Status::Ok();
}

}  // namespace mocapsolve
