#include "io/fbx_writer.h"

#include <cmath>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "io/atomic_file.h"
#include "io/curve_key_reduction.h"
#include "io/fbx_binary.h"
#include "io/input_limits.h"
#include "io/motion_samples.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/frame_rate.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

using fbx::Node;

constexpr int64_t kTicksPerSecond = 46186158000;  // FBX 7.x KTime units per second.
constexpr std::string_view kNameClassSeparator("\x00\x01", 2);

// FBX's RotationOrder enum, indexed by our EulerOrder (the same matrix): ours names the
// leftmost factor first, FBX the axis applied first. kXYZ (Rx Ry Rz) is FBX ZYX (5), ...
int FbxRotationOrder(EulerOrder order) {
  switch (order) {  // FBX: 0 XYZ, 1 XZY, 2 YZX, 3 YXZ, 4 ZXY, 5 ZYX.
    case EulerOrder::kXYZ: return 5;
    case EulerOrder::kXZY: return 2;
    case EulerOrder::kYXZ: return 4;
    case EulerOrder::kYZX: return 1;
    case EulerOrder::kZXY: return 3;
    case EulerOrder::kZYX: return 0;
  }
  return 0;
}

// "name\x00\x01Class", FBX's object name.
std::string NameClass(const std::string& name, const char* cls) {
  std::string out = name;
  out += kNameClassSeparator;
  out += cls;
  return out;
}

Status CheckName(const std::string& name, const std::string& what) {
  if (name.empty()) return Status::Error(what + ": empty name (FBX objects need one)");
  if (name.size() >= (size_t{1} << 31)) return Status::Error(what + ": name over 2^31 bytes");
  if (name.find('\0') != std::string::npos) {
    return Status::Error(what + " " + QuoteToken(name) + ": name holds a NUL byte, which FBX cannot store");
  }
  return Status::Ok();
}

// Properties70 entries: P "name" "type" "label" "flags" values...
Node& P(Node* props, const char* name, const char* type, const char* label, const char* flags) {
  return props->AddChild("P").String(name).String(type).String(label).String(flags);
}
void PInt(Node* props, const char* name, int value) { P(props, name, "int", "Integer", "").Int32(value); }
void PEnum(Node* props, const char* name, int value) { P(props, name, "enum", "", "").Int32(value); }
void PBool(Node* props, const char* name, bool value) { P(props, name, "bool", "", "").Int32(value ? 1 : 0); }
void PDouble(Node* props, const char* name, double value) { P(props, name, "double", "Number", "").Double(value); }
void PTime(Node* props, const char* name, int64_t value) { P(props, name, "KTime", "Time", "").Int64(value); }
void PString(Node* props, const char* name, const std::string& value) { P(props, name, "KString", "", "").String(value); }
void PVector(Node* props, const char* name, const char* type, const char* label, const char* flags,
             const Eigen::Vector3d& v) {
  P(props, name, type, label, flags).Double(v.x()).Double(v.y()).Double(v.z());
}

std::vector<double> MatrixArray(const Eigen::Matrix4d& m) {  // Column-major, as FBX stores them.
  return std::vector<double>(m.data(), m.data() + 16);
}

// Of the two Euler triples of one rotation, (a, b, c) and (a + pi, pi - b, c + pi), each
// shifted componentwise by multiples of 2 pi, the one nearest `previous` (no wrapping:
// consecutive keys never differ by a full turn).
Eigen::Vector3d NearestEquivalentEuler(const Eigen::Vector3d& angles, const Eigen::Vector3d& previous) {
  const Eigen::Vector3d candidates[2] = {angles, Eigen::Vector3d(angles[0] + kPi, kPi - angles[1], angles[2] + kPi)};
  Eigen::Vector3d best = angles;
  double best_distance = INFINITY;
  for (Eigen::Vector3d candidate : candidates) {
    for (int k = 0; k < 3; ++k) candidate[k] += 2.0 * kPi * std::round((previous[k] - candidate[k]) / (2.0 * kPi));
    const double distance = (candidate - previous).squaredNorm();
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

// Angles about x, y, z (degrees) of q in `order`.
Eigen::Vector3d ByAxisDegrees(const Eigen::Vector3d& angles_in_order, EulerOrder order) {
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) out[EulerAxis(order, i)] = RadToDeg(angles_in_order[i]);
  return out;
}

// Samples: MotionSamples or CompactSamples (io/motion_samples.h).
template <class Samples>
class SceneBuilder {
 public:
  SceneBuilder(const Skeleton& skeleton, const Samples& motion, const FbxWriteOptions& options,
               const FbxSkinnedMesh* mesh)
      : skeleton_(skeleton), motion_(motion), options_(options), mesh_(mesh) {}

  // The file's bytes to `sink` (fbx::EncodeFbxBinary).
  Status Build(const fbx::ByteSink& sink);

 private:
  int64_t NewId() { return next_id_++; }
  // The children every Model ends with (after its Properties70), counted in the header.
  void FinishModel(Node* model) {
    model->AddChild("MultiLayer").Int32(0);
    model->AddChild("MultiTake").Int32(0);
    model->AddChild("Shading").Char('T');
    model->AddChild("Culling").String("CullingOff");
    ++models_;
  }
  void Connect(int64_t child, int64_t parent) { connections_.AddChild("C").String("OO").Int64(child).Int64(parent); }
  void ConnectProperty(int64_t child, int64_t parent, const char* property) {
    connections_.AddChild("C").String("OP").Int64(child).Int64(parent).String(property);
  }
  EulerOrder JointOrder(int j) const;
  double UnitScaleFactor() const;
  // The take's rate, an integer when within 1e-5 of one (NominalFrameRate): FBX names whole rates.
  double FrameRate() const { return NominalFrameRate(motion_.frame_rate()); }
  int64_t KeyTime(int frame) const {
    return static_cast<int64_t>(std::llround(frame * static_cast<double>(kTicksPerSecond) / FrameRate()));
  }
  void AddHeader(std::vector<Node>* top);
  void AddGlobalSettings(std::vector<Node>* top);
  int64_t AddLimbNode(const std::string& name, const Eigen::Vector3d& translation, const Eigen::Quaterniond& rotation,
                      const Eigen::Quaterniond& pre_rotation, EulerOrder order, bool t_animated, bool r_animated);
  void AddMesh(const std::vector<int64_t>& joint_models);
  void AddAnimation(const std::vector<int64_t>& joint_models);
  void AddCurve(int64_t curve_node, const char* channel, const std::vector<float>& values, double default_value,
                double tolerance);
  // FbxWriteOptions::key_tolerance_mm in the file's length unit (UnitScaleFactor: cm per unit).
  double KeyToleranceInFileUnits() const { return options_.key_tolerance_mm / (10.0 * UnitScaleFactor()); }
  // Per joint, the key reduction's bound on its rotation curves (degrees) and its
  // translation curves (file units), so that no point moves by more than the option's bound.
  struct KeyTolerances {
    std::vector<double> rotation_degrees;
    std::vector<double> translation;
  };
  KeyTolerances KeyTolerancesOfJoints() const;
  // Joint j's "R" curve node on Lcl Rotation with its three curves; `values` is workspace.
  void AddRotationCurves(int j, int64_t joint_model, int64_t layer, double tolerance, std::vector<float> values[3]);

  const Skeleton& skeleton_;
  const Samples& motion_;
  const FbxWriteOptions& options_;
  const FbxSkinnedMesh* mesh_;
  int64_t next_id_ = 1000000;
  Node objects_{"Objects"};
  Node connections_{"Connections"};
  std::vector<bool> translation_animated_;
  std::vector<bool> rotation_animated_;
  std::vector<Eigen::Vector3d> rest_translations_;
  std::vector<Eigen::Quaterniond> rest_rotations_;
  int64_t time_stop_ = 0;
  // Object counts by type, for Definitions.
  int models_ = 0, attributes_ = 0, geometries_ = 0, materials_ = 0, deformers_ = 0, poses_ = 0;
  int stacks_ = 0, layers_ = 0, curve_nodes_ = 0, curves_ = 0;
};

template <class Samples>
EulerOrder SceneBuilder<Samples>::JointOrder(int j) const {
  // FBX evaluates PreRotation in XYZ order (the SDK, assimp, current Blender); Blender
  // 3.4 uses the joint's RotationOrder instead, so a joint with both is written in XYZ.
  if (skeleton_.has_rest_rotation(j)) return EulerOrder::kZYX;
  if (options_.euler_order) return *options_.euler_order;
  const std::vector<int>& axes = skeleton_.rotation_axes(j);
  bool from_channels = false;
  for (Channel c : skeleton_.joint(j).channels) {
    from_channels = from_channels || c == Channel::kXrotation || c == Channel::kYrotation || c == Channel::kZrotation;
  }
  if (from_channels && axes.size() == 3) return EulerOrderFromAxes(axes[0], axes[1], axes[2]);
  return EulerOrder::kZYX;  // FBX's default, eEulerXYZ.
}

template <class Samples>
double SceneBuilder<Samples>::UnitScaleFactor() const {
  if (options_.unit_scale_factor > 0.0) return options_.unit_scale_factor;
  if (skeleton_.unit().known()) return skeleton_.unit().metres_per_unit * 100.0;
  return 1.0;  // Unknown (BVH): centimetres, FBX's own unit.
}

template <class Samples>
void SceneBuilder<Samples>::AddHeader(std::vector<Node>* top) {
  Node& header = top->emplace_back("FBXHeaderExtension");
  header.AddChild("FBXHeaderVersion").Int32(1003);
  header.AddChild("FBXVersion").Int32(fbx::kFbxVersion);
  header.AddChild("EncryptionType").Int32(0);
  Node& stamp = header.AddChild("CreationTimeStamp");
  stamp.AddChild("Version").Int32(1000);
  const int fixed_time[] = {1970, 1, 1, 10, 0, 0, 0};  // Matches CreationTime below.
  const char* fields[] = {"Year", "Month", "Day", "Hour", "Minute", "Second", "Millisecond"};
  for (int i = 0; i < 7; ++i) stamp.AddChild(fields[i]).Int32(fixed_time[i]);
  header.AddChild("Creator").String("mocapsolve");
  Node& info = header.AddChild("SceneInfo").String(NameClass("GlobalInfo", "SceneInfo")).String("UserData");
  info.AddChild("Type").String("UserData");
  info.AddChild("Version").Int32(100);
  Node& meta = info.AddChild("MetaData");
  meta.AddChild("Version").Int32(100);
  for (const char* field : {"Title", "Subject", "Author", "Keywords", "Revision", "Comment"}) {
    meta.AddChild(field).String("");
  }
  Node& props = info.AddChild("Properties70");
  P(&props, "Original", "Compound", "", "");
  P(&props, "Original|ApplicationVendor", "KString", "", "").String("mocapsolve");
  P(&props, "Original|ApplicationName", "KString", "", "").String("mocapsolve");
  P(&props, "LastSaved", "Compound", "", "");
  P(&props, "LastSaved|ApplicationVendor", "KString", "", "").String("mocapsolve");
  P(&props, "LastSaved|ApplicationName", "KString", "", "").String("mocapsolve");
  top->emplace_back("FileId").Raw(fbx::FileIdBytes());
  top->emplace_back("CreationTime").String(fbx::CreationTimeString());
  top->emplace_back("Creator").String("mocapsolve");
}

template <class Samples>
void SceneBuilder<Samples>::AddGlobalSettings(std::vector<Node>* top) {
  Node& settings = top->emplace_back("GlobalSettings");
  settings.AddChild("Version").Int32(1000);
  Node& props = settings.AddChild("Properties70");
  PInt(&props, "UpAxis", 1);
  PInt(&props, "UpAxisSign", 1);
  PInt(&props, "FrontAxis", 2);
  PInt(&props, "FrontAxisSign", 1);
  PInt(&props, "CoordAxis", 0);
  PInt(&props, "CoordAxisSign", 1);
  PInt(&props, "OriginalUpAxis", 1);
  PInt(&props, "OriginalUpAxisSign", 1);
  PDouble(&props, "UnitScaleFactor", UnitScaleFactor());
  PDouble(&props, "OriginalUnitScaleFactor", UnitScaleFactor());
  PVector(&props, "AmbientColor", "ColorRGB", "Color", "", Eigen::Vector3d::Zero());
  PString(&props, "DefaultCamera", "Producer Perspective");
  // FBX's TimeMode enum for the rates it names; 14 = custom (CustomFrameRate).
  static const struct { double fps; int mode; } kModes[] = {
      {120, 1}, {100, 2}, {60, 3}, {50, 4}, {48, 5}, {30, 6}, {25, 10}, {24, 11}, {96, 15}, {72, 16}};
  int mode = 14;
  for (const auto& m : kModes) {
    if (std::abs(FrameRate() - m.fps) < 1e-9 * m.fps) mode = m.mode;
  }
  PEnum(&props, "TimeMode", mode);
  PTime(&props, "TimeSpanStart", 0);
  PTime(&props, "TimeSpanStop", time_stop_);
  PDouble(&props, "CustomFrameRate", FrameRate());
}

template <class Samples>
int64_t SceneBuilder<Samples>::AddLimbNode(const std::string& name, const Eigen::Vector3d& translation,
                                  const Eigen::Quaterniond& rotation, const Eigen::Quaterniond& pre_rotation,
                                  EulerOrder order, bool t_animated, bool r_animated) {
  const int64_t attribute = NewId();
  Node& attr = objects_.AddChild("NodeAttribute").Int64(attribute).String(NameClass(name, "NodeAttribute"))
                   .String("LimbNode");
  attr.AddChild("TypeFlags").String("Skeleton");
  ++attributes_;
  const int64_t model = NewId();
  Node& node = objects_.AddChild("Model").Int64(model).String(NameClass(name, "Model")).String("LimbNode");
  node.AddChild("Version").Int32(232);
  Node& props = node.AddChild("Properties70");
  PBool(&props, "RotationActive", true);
  PEnum(&props, "RotationOrder", FbxRotationOrder(order));
  PEnum(&props, "InheritType", 1);  // RSrs: the parent's scale does not shear the child.
  if (pre_rotation.vec().norm() > 0.0) {
    PVector(&props, "PreRotation", "Vector3D", "Vector", "",
            ByAxisDegrees(EulerFromQuaternion(pre_rotation, EulerOrder::kZYX), EulerOrder::kZYX));
  }
  PVector(&props, "Lcl Translation", "Lcl Translation", "", t_animated ? "A+" : "A", translation);
  PVector(&props, "Lcl Rotation", "Lcl Rotation", "", r_animated ? "A+" : "A",
          ByAxisDegrees(EulerFromQuaternion(rotation, order), order));
  PVector(&props, "Lcl Scaling", "Lcl Scaling", "", "A", Eigen::Vector3d::Ones());
  PInt(&props, "DefaultAttributeIndex", 0);
  FinishModel(&node);
  Connect(attribute, model);
  return model;
}

template <class Samples>
void SceneBuilder<Samples>::AddCurve(int64_t curve_node, const char* channel, const std::vector<float>& values,
                            double default_value, double tolerance) {
  // A constant curve keeps its first and last key: the clip's length stays in every curve,
  // and assimp drops a curve of one key per axis that is within 3.5e-4 of the model's
  // default value (IsRedundantAnimationData), which would lose such a difference.
  const CurveKeys keys = ReduceLinearKeys(values, tolerance);
  std::vector<int64_t> times;
  for (int k : keys.frames) times.push_back(KeyTime(k));
  const int64_t id = NewId();
  Node& curve = objects_.AddChild("AnimationCurve").Int64(id).String(NameClass("", "AnimCurve")).String("");
  curve.AddChild("Default").Double(default_value);
  curve.AddChild("KeyVer").Int32(4008);
  curve.AddChild("KeyTime").Int64Array(times);
  curve.AddChild("KeyValueFloat").FloatArray(keys.values);
  // One attribute for all keys: linear interpolation (bit 2) with the SDK's default tangent
  // flags (as Blender writes them).
  curve.AddChild("KeyAttrFlags").Int32Array({(1 << 2) | (1 << 8) | (1 << 13) | (1 << 14)});
  curve.AddChild("KeyAttrDataFloat").FloatArray({0.0f, 0.0f, 9.419963346924634e-30f, 0.0f});
  curve.AddChild("KeyAttrRefCount").Int32Array({static_cast<int32_t>(times.size())});
  ++curves_;
  ConnectProperty(id, curve_node, channel);
}

template <class Samples>
typename SceneBuilder<Samples>::KeyTolerances SceneBuilder<Samples>::KeyTolerancesOfJoints() const {
  // A point p (joint or end site) is moved by the translation curves of itself and of each
  // joint above it, and by the rotation curves of each joint strictly above it: m(p) curve
  // sets. Joint j's rotation keys, each of three Euler angles off by at most tau_j, turn it
  // by at most 3 tau_j, which moves a point below it by at most 3 tau_j r_j (r_j its reach:
  // the longest path of offsets from j to a point below it); its translation keys move j and
  // everything below by at most eps_j. With M_j the largest m(p) over the points a set of j's
  // moves, tau_j = E / (3 r_j M_j) and eps_j = E / M_j: along any path the shares add to at
  // most E, so no point of the file moves by more than E.
  const int nj = skeleton_.num_joints();
  const int nf = motion_.num_frames();
  std::vector<double> length(nj, 0.0);  // |offset|, its largest over the take where animated.
  for (int j = 0; j < nj; ++j) {
    length[j] = rest_translations_[j].norm();
    for (int f = 0; translation_animated_[j] && f < nf; ++f) {
      length[j] = std::max(length[j], motion_.translation(f, j).norm());
    }
  }
  std::vector<int> sets(nj, 0);  // m(j).
  for (int j = 0; j < nj; ++j) {  // Parents come first.
    const int parent = skeleton_.parent(j);
    sets[j] = (parent < 0 ? 0 : sets[parent] + (rotation_animated_[parent] ? 1 : 0)) + (translation_animated_[j] ? 1 : 0);
  }
  std::vector<double> reach(nj, 0.0);
  std::vector<int> below(nj, 0);     // Largest m(p) over points strictly below j.
  std::vector<int> at_or_below(nj);  // The same with j itself.
  std::vector<bool> leaf(nj, true);
  for (int j = 0; j < nj; ++j) {
    if (skeleton_.parent(j) >= 0) leaf[skeleton_.parent(j)] = false;
  }
  for (const EndSite& site : skeleton_.end_sites()) {
    reach[site.parent] = std::max(reach[site.parent], site.offset.norm());
    below[site.parent] = std::max(below[site.parent], sets[site.parent] + (rotation_animated_[site.parent] ? 1 : 0));
    leaf[site.parent] = false;
  }
  for (int j = nj - 1; j >= 0; --j) {  // Children are done before their parents.
    if (leaf[j]) {  // A point at its own bone's length stands for its skin.
      reach[j] = length[j];
      below[j] = sets[j] + (rotation_animated_[j] ? 1 : 0);
    }
    at_or_below[j] = std::max(sets[j], below[j]);
    const int parent = skeleton_.parent(j);
    if (parent < 0) continue;
    reach[parent] = std::max(reach[parent], length[j] + reach[j]);
    below[parent] = std::max(below[parent], at_or_below[j]);
  }
  const double tolerance = KeyToleranceInFileUnits();
  KeyTolerances tolerances{std::vector<double>(nj, 0.0), std::vector<double>(nj, 0.0)};
  for (int j = 0; j < nj; ++j) {
    if (rotation_animated_[j] && reach[j] > 0.0 && below[j] > 0) {
      tolerances.rotation_degrees[j] = tolerance / (3.0 * reach[j] * below[j]) * 180.0 / M_PI;
    }
    if (translation_animated_[j]) tolerances.translation[j] = tolerance / std::max(at_or_below[j], 1);
  }
  return tolerances;
}

template <class Samples>
void SceneBuilder<Samples>::AddRotationCurves(int j, int64_t joint_model, int64_t layer, double tolerance,
                                     std::vector<float> values[3]) {
  const EulerOrder order = JointOrder(j);
  const int nf = motion_.num_frames();
  const char* axes[3] = {"d|X", "d|Y", "d|Z"};
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (int f = 0; f < nf; ++f) {
    Eigen::Vector3d angles = EulerFromQuaternion(motion_.rotation(f, j), order);
    if (f > 0) angles = NearestEquivalentEuler(angles, previous);
    previous = angles;
    const Eigen::Vector3d by_axis = ByAxisDegrees(angles, order);
    if (f == 0) first = by_axis;
    for (int a = 0; a < 3; ++a) values[a][f] = static_cast<float>(by_axis[a]);
  }
  const int64_t rotation_node = NewId();
  Node& rnode = objects_.AddChild("AnimationCurveNode").Int64(rotation_node)
                    .String(NameClass("R", "AnimCurveNode")).String("");
  Node& rprops = rnode.AddChild("Properties70");
  for (int a = 0; a < 3; ++a) P(&rprops, axes[a], "Number", "", "A").Double(first[a]);
  ++curve_nodes_;
  Connect(rotation_node, layer);
  ConnectProperty(rotation_node, joint_model, "Lcl Rotation");
  for (int a = 0; a < 3; ++a) AddCurve(rotation_node, axes[a], values[a], first[a], tolerance);
}

template <class Samples>
void SceneBuilder<Samples>::AddAnimation(const std::vector<int64_t>& joint_models) {
  const int64_t stack = NewId();
  Node& stack_node = objects_.AddChild("AnimationStack").Int64(stack)
                         .String(NameClass(options_.take_name, "AnimStack")).String("");
  Node& stack_props = stack_node.AddChild("Properties70");
  PTime(&stack_props, "LocalStart", 0);
  PTime(&stack_props, "LocalStop", time_stop_);
  PTime(&stack_props, "ReferenceStart", 0);
  PTime(&stack_props, "ReferenceStop", time_stop_);
  ++stacks_;
  const int64_t layer = NewId();
  objects_.AddChild("AnimationLayer").Int64(layer).String(NameClass("BaseLayer", "AnimLayer")).String("");
  ++layers_;
  Connect(layer, stack);
  const int nf = motion_.num_frames();
  const char* axes[3] = {"d|X", "d|Y", "d|Z"};
  const KeyTolerances tolerances = KeyTolerancesOfJoints();
  for (int j = 0; j < skeleton_.num_joints(); ++j) {
    std::vector<float> values[3];
    for (auto& v : values) v.resize(nf);
    if (rotation_animated_[j]) AddRotationCurves(j, joint_models[j], layer, tolerances.rotation_degrees[j], values);
    if (!translation_animated_[j]) continue;
    for (int f = 0; f < nf; ++f) {
      const Eigen::Vector3d t = motion_.translation(f, j);
      for (int a = 0; a < 3; ++a) values[a][f] = static_cast<float>(t[a]);
    }
    const int64_t translation_node = NewId();
    Node& tnode = objects_.AddChild("AnimationCurveNode").Int64(translation_node)
                      .String(NameClass("T", "AnimCurveNode")).String("");
    Node& tprops = tnode.AddChild("Properties70");
    const Eigen::Vector3d t0 = motion_.translation(0, j);
    for (int a = 0; a < 3; ++a) P(&tprops, axes[a], "Number", "", "A").Double(t0[a]);
    ++curve_nodes_;
    Connect(translation_node, layer);
    ConnectProperty(translation_node, joint_models[j], "Lcl Translation");
    for (int a = 0; a < 3; ++a) AddCurve(translation_node, axes[a], values[a], t0[a], tolerances.translation[j]);
  }
}

template <class Samples>
void SceneBuilder<Samples>::AddMesh(const std::vector<int64_t>& joint_models) {
  const SkinnedMesh& mesh = *mesh_->mesh;
  const Eigen::Matrix3Xi& triangles = *mesh_->triangles;
  const int64_t geometry = NewId();
  Node& geom = objects_.AddChild("Geometry").Int64(geometry).String(NameClass(mesh_->name, "Geometry")).String("Mesh");
  geom.AddChild("Properties70");
  geom.AddChild("GeometryVersion").Int32(124);
  const int nv = mesh.num_vertices();
  std::vector<double> vertices(mesh.rest_positions().data(), mesh.rest_positions().data() + 3 * nv);
  geom.AddChild("Vertices").DoubleArray(vertices);
  std::vector<int32_t> polygons(3 * triangles.cols());
  for (int t = 0; t < triangles.cols(); ++t) {
    polygons[3 * t] = triangles(0, t);
    polygons[3 * t + 1] = triangles(1, t);
    polygons[3 * t + 2] = ~triangles(2, t);  // The last vertex of a polygon, stored as -index - 1.
  }
  geom.AddChild("PolygonVertexIndex").Int32Array(polygons);
  if (mesh.has_normals()) {
    Node& normals = geom.AddChild("LayerElementNormal").Int32(0);
    normals.AddChild("Version").Int32(101);
    normals.AddChild("Name").String("");
    normals.AddChild("MappingInformationType").String("ByVertice");
    normals.AddChild("ReferenceInformationType").String("Direct");
    normals.AddChild("Normals").DoubleArray(
        std::vector<double>(mesh.rest_normals().data(), mesh.rest_normals().data() + 3 * nv));
  }
  if (mesh.has_texcoords()) {  // Per polygon vertex, indexing one UV per vertex; FBX's v runs up, glTF's down.
    Node& uv = geom.AddChild("LayerElementUV").Int32(0);
    uv.AddChild("Version").Int32(101);
    uv.AddChild("Name").String("UVMap");
    uv.AddChild("MappingInformationType").String("ByPolygonVertex");
    uv.AddChild("ReferenceInformationType").String("IndexToDirect");
    std::vector<double> values(2 * nv);
    for (int v = 0; v < nv; ++v) {
      values[2 * v] = mesh.texcoords()(0, v);
      values[2 * v + 1] = 1.0 - mesh.texcoords()(1, v);
    }
    uv.AddChild("UV").DoubleArray(values);
    uv.AddChild("UVIndex").Int32Array(std::vector<int32_t>(triangles.data(), triangles.data() + triangles.size()));
  }
  Node& material_layer = geom.AddChild("LayerElementMaterial").Int32(0);
  material_layer.AddChild("Version").Int32(101);
  material_layer.AddChild("Name").String("");
  material_layer.AddChild("MappingInformationType").String("AllSame");
  material_layer.AddChild("ReferenceInformationType").String("IndexToDirect");
  material_layer.AddChild("Materials").Int32Array({0});
  // Layer 0 lists the elements above (after them, as the SDK and Blender write it).
  Node& layer = geom.AddChild("Layer").Int32(0);
  layer.AddChild("Version").Int32(100);
  for (const char* type : {"LayerElementNormal", "LayerElementUV", "LayerElementMaterial"}) {
    if (std::string_view(type) == "LayerElementNormal" && !mesh.has_normals()) continue;
    if (std::string_view(type) == "LayerElementUV" && !mesh.has_texcoords()) continue;
    Node& element = layer.AddChild("LayerElement");
    element.AddChild("Type").String(type);
    element.AddChild("TypedIndex").Int32(0);
  }
  ++geometries_;

  const int64_t model = NewId();
  Node& node = objects_.AddChild("Model").Int64(model).String(NameClass(mesh_->name, "Model")).String("Mesh");
  node.AddChild("Version").Int32(232);
  Node& props = node.AddChild("Properties70");
  PEnum(&props, "InheritType", 1);
  PInt(&props, "DefaultAttributeIndex", 0);
  FinishModel(&node);
  Connect(model, 0);
  Connect(geometry, model);

  const int64_t material = NewId();
  Node& mat = objects_.AddChild("Material").Int64(material).String(NameClass("grey", "Material")).String("");
  mat.AddChild("Version").Int32(102);
  mat.AddChild("ShadingModel").String("phong");
  mat.AddChild("MultiLayer").Int32(0);
  Node& mat_props = mat.AddChild("Properties70");
  PString(&mat_props, "ShadingModel", "phong");
  PVector(&mat_props, "DiffuseColor", "Color", "", "A", Eigen::Vector3d::Constant(0.8));
  P(&mat_props, "DiffuseFactor", "Number", "", "A").Double(1.0);
  PVector(&mat_props, "SpecularColor", "Color", "", "A", Eigen::Vector3d::Constant(0.2));
  P(&mat_props, "Opacity", "Number", "", "A").Double(1.0);
  ++materials_;
  Connect(material, model);

  const int64_t skin = NewId();
  Node& skin_node = objects_.AddChild("Deformer").Int64(skin).String(NameClass(mesh_->name, "Deformer")).String("Skin");
  skin_node.AddChild("Version").Int32(101);
  skin_node.AddChild("Link_DeformAcuracy").Double(50.0);
  ++deformers_;
  Connect(skin, geometry);

  const int nj = skeleton_.num_joints();
  std::vector<std::vector<int32_t>> indexes(nj);
  std::vector<std::vector<double>> weights(nj);
  for (int v = 0; v < nv; ++v) {
    for (int k = mesh.weight_begin(v); k < mesh.weight_end(v); ++k) {
      indexes[mesh.weight_joint(k)].push_back(v);
      weights[mesh.weight_joint(k)].push_back(mesh.weight(k));
    }
  }
  const int64_t pose = NewId();
  Node& pose_node = objects_.AddChild("Pose").Int64(pose).String(NameClass(mesh_->name, "Pose")).String("BindPose");
  pose_node.AddChild("Type").String("BindPose");
  pose_node.AddChild("Version").Int32(100);
  pose_node.AddChild("NbPoseNodes").Int32(nj + 1);
  Node& mesh_pose = pose_node.AddChild("PoseNode");
  mesh_pose.AddChild("Node").Int64(model);
  mesh_pose.AddChild("Matrix").DoubleArray(MatrixArray(Eigen::Matrix4d::Identity()));
  ++poses_;
  for (int j = 0; j < nj; ++j) {
    const Eigen::Matrix4d world_from_bind = mesh.joint_from_bind(j).inverse().matrix();
    const int64_t cluster = NewId();
    Node& c = objects_.AddChild("Deformer").Int64(cluster).String(NameClass(skeleton_.name(j), "SubDeformer"))
                  .String("Cluster");
    c.AddChild("Version").Int32(100);
    c.AddChild("UserData").String("").String("");
    if (!indexes[j].empty()) {
      c.AddChild("Indexes").Int32Array(indexes[j]);
      c.AddChild("Weights").DoubleArray(weights[j]);
    }
    c.AddChild("Transform").DoubleArray(MatrixArray(mesh.joint_from_bind(j).matrix()));
    c.AddChild("TransformLink").DoubleArray(MatrixArray(world_from_bind));
    ++deformers_;
    Connect(cluster, skin);
    Connect(joint_models[j], cluster);
    Node& joint_pose = pose_node.AddChild("PoseNode");
    joint_pose.AddChild("Node").Int64(joint_models[j]);
    joint_pose.AddChild("Matrix").DoubleArray(MatrixArray(world_from_bind));
  }
}

template <class Samples>
Status SceneBuilder<Samples>::Build(const fbx::ByteSink& sink) {
  const int nj = skeleton_.num_joints();
  const int nf = motion_.num_frames();
  time_stop_ = KeyTime(nf - 1);
  rest_translations_.resize(nj);
  rest_rotations_.resize(nj);
  for (int j = 0; j < nj; ++j) {
    rest_translations_[j] = options_.rest_pose ? options_.rest_pose->translations[j] : skeleton_.offset(j);
    rest_rotations_[j] = options_.rest_pose ? options_.rest_pose->rotations[j] : Eigen::Quaterniond::Identity();
  }
  translation_animated_.assign(nj, false);
  translation_animated_[0] = true;
  for (int j = 1; j < nj; ++j) {
    const double tolerance = 1e-9 * (rest_translations_[j].norm() + 1.0);
    for (int f = 0; f < nf && !translation_animated_[j]; ++f) {
      translation_animated_[j] = (motion_.translation(f, j) - rest_translations_[j]).norm() > tolerance;
    }
  }
  // A joint that never turns from its default rotation gets no rotation curves (importers
  // keep the model's Lcl Rotation): still fingers are a third of a character's curves.
  rotation_animated_.assign(nj, false);
  rotation_animated_[0] = true;  // The root's curves carry the take's length.
  for (int j = 1; j < nj; ++j) {
    for (int f = 0; f < nf && !rotation_animated_[j]; ++f) {
      rotation_animated_[j] = motion_.rotation(f, j).angularDistance(rest_rotations_[j]) > 1e-9;
    }
  }
  std::vector<int64_t> joint_models(nj);
  for (int j = 0; j < nj; ++j) {
    const Eigen::Quaterniond pre = skeleton_.has_rest_rotation(j) ? skeleton_.rest_rotation(j)
                                                                   : Eigen::Quaterniond::Identity();
    joint_models[j] = AddLimbNode(skeleton_.name(j), rest_translations_[j], rest_rotations_[j], pre, JointOrder(j),
                                  translation_animated_[j], rotation_animated_[j]);
    Connect(joint_models[j], skeleton_.parent(j) < 0 ? 0 : joint_models[skeleton_.parent(j)]);
  }
  for (const EndSite& site : skeleton_.end_sites()) {
    const int64_t model = AddLimbNode(site.name, site.offset, Eigen::Quaterniond::Identity(),
                                      Eigen::Quaterniond::Identity(), EulerOrder::kZYX, false, false);
    Connect(model, joint_models[site.parent]);
  }
  if (mesh_ != nullptr) AddMesh(joint_models);
  AddAnimation(joint_models);

  std::vector<Node> top;
  top.reserve(16);  // Nodes are moved into place below; no reallocation while building.
  AddHeader(&top);
  AddGlobalSettings(&top);
  Node& documents = top.emplace_back("Documents");
  documents.AddChild("Count").Int32(1);
  Node& document = documents.AddChild("Document").Int64(NewId()).String("Scene").String("Scene");
  Node& doc_props = document.AddChild("Properties70");
  P(&doc_props, "SourceObject", "object", "", "");
  PString(&doc_props, "ActiveAnimStackName", options_.take_name);
  document.AddChild("RootNode").Int64(0);
  top.emplace_back("References");
  Node& definitions = top.emplace_back("Definitions");
  definitions.AddChild("Version").Int32(100);
  const std::pair<const char*, int> types[] = {
      {"GlobalSettings", 1},   {"Model", models_},         {"NodeAttribute", attributes_},
      {"Geometry", geometries_}, {"Material", materials_},   {"Deformer", deformers_},
      {"Pose", poses_},        {"AnimationStack", stacks_}, {"AnimationLayer", layers_},
      {"AnimationCurveNode", curve_nodes_}, {"AnimationCurve", curves_}};
  int total = 0;
  for (const auto& [type, count] : types) total += count;
  definitions.AddChild("Count").Int32(total);
  for (const auto& [type, count] : types) {
    if (count == 0) continue;
    definitions.AddChild("ObjectType").String(type).AddChild("Count").Int32(count);
  }
  top.push_back(std::move(objects_));
  top.push_back(std::move(connections_));
  Node& takes = top.emplace_back("Takes");
  takes.AddChild("Current").String(options_.take_name);
  Node& take = takes.AddChild("Take").String(options_.take_name);
  take.AddChild("FileName").String(options_.take_name + ".tak");
  take.AddChild("LocalTime").Int64(0).Int64(time_stop_);
  take.AddChild("ReferenceTime").Int64(0).Int64(time_stop_);
  std::vector<const Node*> pointers;
  for (const Node& node : top) pointers.push_back(&node);
  return fbx::EncodeFbxBinary(pointers, sink);
}

Status CheckDepth(int depth, const std::string& what, const std::string& name) {
  if (depth <= kMaxFbxSkeletonDepth) return Status::Ok();
  return Status::Error(what + " " + QuoteToken(name) + ": " + std::to_string(depth) +
                       " levels below the root, deeper than the " + std::to_string(kMaxFbxSkeletonDepth) +
                       " FBX importers read (Blender's recurses once per level)");
}

template <class Samples>
Status CheckWritable(const Skeleton& skeleton, const Samples& motion, const FbxWriteOptions& options,
                     const FbxSkinnedMesh* mesh) {
  if (skeleton.num_joints() == 0) return Status::Error("the skeleton has no joints");
  std::vector<int> depth(skeleton.num_joints(), 0);  // Joints are in preorder: parents first.
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    const std::string what = "joint " + std::to_string(j);
    if (Status s = CheckName(skeleton.name(j), what); !s.ok()) return s;
    if (skeleton.parent(j) >= 0) depth[j] = depth[skeleton.parent(j)] + 1;
    if (Status s = CheckDepth(depth[j], what, skeleton.name(j)); !s.ok()) return s;
  }
  for (size_t e = 0; e < skeleton.end_sites().size(); ++e) {
    const EndSite& site = skeleton.end_sites()[e];
    const std::string what = "end site " + std::to_string(e);
    if (Status s = CheckName(site.name, what); !s.ok()) return s;
    if (Status s = CheckDepth(depth[site.parent] + 1, what, site.name); !s.ok()) return s;
  }
  if (Status s = CheckName(options.take_name, "take"); !s.ok()) return s;
  if (!(options.unit_scale_factor >= 0.0) || !std::isfinite(options.unit_scale_factor)) {
    return Status::Error("unit scale factor must be positive (or 0: from the skeleton's unit)");
  }
  if (motion.num_frames() == 0) return Status::Error("the motion has no frames");
  if (!(motion.frame_rate() > 0.0) || !std::isfinite(motion.frame_rate())) {
    return Status::Error("frame rate must be positive, got " + ShortNumber(motion.frame_rate()));
  }
  if (!(motion.num_frames() / motion.frame_rate() * static_cast<double>(kTicksPerSecond) < 9e18)) {
    return Status::Error("the clip is too long for FBX key times");
  }
  if (Status s = motion.Validate(skeleton); !s.ok()) return s;
  if (options.rest_pose) {
    if (Status s = ValidatePose(skeleton, *options.rest_pose, "rest pose"); !s.ok()) return s;
  }
  if (mesh != nullptr) {
    if (mesh->mesh == nullptr || mesh->triangles == nullptr) return Status::Error("mesh: no vertices or triangles given");
    if (Status s = CheckName(mesh->name, "mesh"); !s.ok()) return s;
    if (mesh->mesh->num_joints() != skeleton.num_joints()) {
      return Status::Error("mesh: bound to " + std::to_string(mesh->mesh->num_joints()) + " joints, the skeleton has " +
                           std::to_string(skeleton.num_joints()));
    }
    const int nv = mesh->mesh->num_vertices();
    for (int t = 0; t < mesh->triangles->cols(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const int v = (*mesh->triangles)(k, t);
        if (v < 0 || v >= nv) {
          return Status::Error("mesh: triangle " + std::to_string(t) + " names vertex " + std::to_string(v) +
                               " of " + std::to_string(nv));
        }
      }
    }
  }
  return Status::Ok();
}

template <class Samples>
Status SerializeSamples(const Skeleton& skeleton, const Samples& motion, const FbxWriteOptions& options,
                        const FbxSkinnedMesh* mesh, std::string* bytes) {
  if (Status s = CheckWritable(skeleton, motion, options, mesh); !s.ok()) {
    return Status::Error("cannot write FBX: " + s.message());
  }
  SceneBuilder<Samples> builder(skeleton, motion, options, mesh);
  std::string out;
  Status status = builder.Build([&out](std::string_view piece) {
    out.append(piece);
    return Status::Ok();
  });
  if (status.ok()) *bytes = std::move(out);
  return status;
}

// Straight into the file (AtomicFileWriter), a megabyte at a time: a long take's bytes are
// never whole in memory beside its scene's records.
template <class Samples>
Status WriteSamples(const std::string& path, const Skeleton& skeleton, const Samples& motion,
                    const FbxWriteOptions& options, const FbxSkinnedMesh* mesh) {
  Status status = CheckWritable(skeleton, motion, options, mesh);
  if (!status.ok()) return Status::Error(path + ": cannot write FBX: " + status.message());
  AtomicFileWriter file;
  status = file.Open(path);
  if (status.ok()) {
    SceneBuilder<Samples> builder(skeleton, motion, options, mesh);
    status = builder.Build([&file](std::string_view piece) { return file.Append(piece.data(), piece.size()); });
  }
  if (status.ok()) status = file.Close();
  return status.ok() || status.message().rfind(path, 0) == 0 ? status : Status::Error(path + ": " + status.message());
}

template <class Samples>
Status WriteCharacterSamples(const std::string& path, const GltfCharacter& character, const Samples& motion,
                             const std::string& take_name, bool animation_only, double key_tolerance_mm) {
  FbxWriteOptions options;
  options.take_name = take_name;
  options.rest_pose = character.rest_pose;
  options.key_tolerance_mm = key_tolerance_mm;
  FbxSkinnedMesh mesh;
  mesh.mesh = &character.mesh;
  mesh.triangles = &character.triangles;
  const bool with_mesh = !animation_only && character.mesh.num_vertices() > 0 && character.triangles.cols() > 0;
  return WriteSamples(path, character.skeleton, motion, options, with_mesh ? &mesh : nullptr);
}

}  // namespace

Status SerializeFbx(const Skeleton& skeleton, const Motion& motion, const FbxWriteOptions& options,
                    const FbxSkinnedMesh* mesh, std::string* bytes) {
  return SerializeSamples(skeleton, MotionSamples(motion), options, mesh, bytes);
}

Status WriteFbx(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                const FbxWriteOptions& options, const FbxSkinnedMesh* mesh) {
  return WriteSamples(path, skeleton, MotionSamples(motion), options, mesh);
}

Status WriteFbxCharacter(const std::string& path, const GltfCharacter& character, const Motion& motion,
                         const std::string& take_name, bool animation_only, double key_tolerance_mm) {
  return WriteCharacterSamples(path, character, MotionSamples(motion), take_name, animation_only, key_tolerance_mm);
}

Status WriteFbxCharacter(const std::string& path, const GltfCharacter& character, const CompactMotion& motion,
                         const std::string& take_name, bool animation_only, double key_tolerance_mm) {
  return WriteCharacterSamples(path, character, CompactSamples(motion), take_name, animation_only, key_tolerance_mm);
}

}  // namespace mocapsolve
