#include "io/fbx_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>

#include "io/atomic_file.h"
#include "io/fbx_binary.h"
#include "io/fbx_reader.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/motion_file.h"
#include "kinematics/compact_motion.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "tests/gltf_test_files.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// A reader of our own for the binary container, independent of the writer's code: the
// record tree with every property decoded (scalars and arrays as doubles, strings as bytes).
struct FbxProperty {
  char type = 0;
  std::string text;             // 'S', 'R'.
  std::vector<double> numbers;  // Scalars (one) and arrays.
};
struct FbxRecord {
  std::string name;
  std::vector<FbxProperty> properties;
  std::vector<FbxRecord> children;
};

template <typename T>
T Read(const std::string& b, size_t* at) {
  T v;
  if (*at + sizeof(T) > b.size()) throw std::runtime_error("truncated");
  std::memcpy(&v, b.data() + *at, sizeof(T));
  *at += sizeof(T);
  return v;
}

template <typename T>
void DecodeArray(const std::string& b, size_t* at, FbxProperty* p) {
  const uint32_t count = Read<uint32_t>(b, at), encoding = Read<uint32_t>(b, at), bytes = Read<uint32_t>(b, at);
  if (*at + bytes > b.size()) throw std::runtime_error("array past the end");
  std::string data(count * sizeof(T), '\0');
  if (encoding == 1) {
    uLongf size = data.size();
    if (uncompress(reinterpret_cast<Bytef*>(&data[0]), &size, reinterpret_cast<const Bytef*>(b.data() + *at), bytes) !=
            Z_OK ||
        size != data.size()) {
      throw std::runtime_error("bad zlib array");
    }
  } else {
    if (bytes != data.size()) throw std::runtime_error("raw array size");
    data.assign(b.data() + *at, bytes);
  }
  *at += bytes;
  for (uint32_t i = 0; i < count; ++i) {
    T v;
    std::memcpy(&v, data.data() + i * sizeof(T), sizeof(T));
    p->numbers.push_back(static_cast<double>(v));
  }
}

// Parses one record at *at (null record: returns false).
bool ParseRecord(const std::string& b, size_t* at, FbxRecord* out) {
  const uint32_t end = Read<uint32_t>(b, at), count = Read<uint32_t>(b, at), length = Read<uint32_t>(b, at);
  const uint8_t name_size = Read<uint8_t>(b, at);
  if (end == 0) {
    if (count != 0 || length != 0 || name_size != 0) throw std::runtime_error("bad null record");
    return false;
  }
  out->name = b.substr(*at, name_size);
  *at += name_size;
  const size_t properties_start = *at;
  for (uint32_t i = 0; i < count; ++i) {
    FbxProperty p;
    p.type = Read<char>(b, at);
    switch (p.type) {
      case 'C': case 'B': p.numbers.push_back(Read<uint8_t>(b, at)); break;
      case 'Y': p.numbers.push_back(Read<int16_t>(b, at)); break;
      case 'I': p.numbers.push_back(Read<int32_t>(b, at)); break;
      case 'L': p.numbers.push_back(static_cast<double>(Read<int64_t>(b, at))); break;
      case 'F': p.numbers.push_back(Read<float>(b, at)); break;
      case 'D': p.numbers.push_back(Read<double>(b, at)); break;
      case 'S': case 'R': {
        const uint32_t n = Read<uint32_t>(b, at);
        p.text = b.substr(*at, n);
        *at += n;
        break;
      }
      case 'i': DecodeArray<int32_t>(b, at, &p); break;
      case 'l': DecodeArray<int64_t>(b, at, &p); break;
      case 'f': DecodeArray<float>(b, at, &p); break;
      case 'd': DecodeArray<double>(b, at, &p); break;
      default: throw std::runtime_error("unknown property type");
    }
    out->properties.push_back(std::move(p));
  }
  if (*at - properties_start != length) throw std::runtime_error("property list length of " + out->name);
  if (*at < end) {  // Children, then a null record.
    while (*at < end - 13) {
      FbxRecord child;
      if (!ParseRecord(b, at, &child)) throw std::runtime_error("null record inside " + out->name);
      out->children.push_back(std::move(child));
    }
    FbxRecord null;
    if (ParseRecord(b, at, &null)) throw std::runtime_error("no null record closing " + out->name);
  }
  if (*at != end) throw std::runtime_error("end offset of " + out->name);
  return true;
}

// The top-level records of a file (header and footer checked).
std::vector<FbxRecord> ParseFbxFile(const std::string& b) {
  if (b.compare(0, 23, std::string("Kaydara FBX Binary  \x00\x1a\x00", 23)) != 0) throw std::runtime_error("magic");
  size_t at = 23;
  if (Read<uint32_t>(b, &at) != 7400) throw std::runtime_error("version");
  std::vector<FbxRecord> top;
  for (;;) {
    FbxRecord r;
    if (!ParseRecord(b, &at, &r)) break;
    top.push_back(std::move(r));
  }
  // Footer: id (16), 4 zeros, padding to 16 (1..16), version, 120 zeros, magic (16).
  const size_t pad = 16 - (at + 20) % 16;
  if (b.size() != at + 20 + pad + 4 + 120 + 16) throw std::runtime_error("footer size");
  return top;
}

const FbxRecord* Find(const std::vector<FbxRecord>& records, const std::string& name) {
  for (const FbxRecord& r : records) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

JointSpec Joint(const std::string& name, int parent, const Eigen::Vector3d& offset) {
  JointSpec spec;
  spec.name = name;
  spec.parent = parent;
  spec.offset = offset;
  return spec;
}

// A small skeleton in cm: a root with translation channels, a spine with a rest rotation,
// arms with different rotation orders, end sites.
Skeleton TestSkeleton() {
  std::vector<JointSpec> joints(6);
  const auto rot = [](const char* order) {
    std::vector<Channel> c;
    for (const char* p = order; *p; ++p) {
      c.push_back(*p == 'X' ? Channel::kXrotation : *p == 'Y' ? Channel::kYrotation : Channel::kZrotation);
    }
    return c;
  };
  joints[0] = Joint("Hips", -1, {0, 90, 0});
  joints[0].channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition};
  for (Channel c : rot("ZXY")) joints[0].channels.push_back(c);
  joints[1] = Joint("Spine", 0, {0, 10, 1});
  joints[1].rest_rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
  joints[1].channels = rot("XYZ");
  joints[2] = Joint("Head", 1, {0, 30, 0});
  joints[2].channels = rot("YZX");
  joints[3] = Joint("LeftArm", 1, {15, 25, 0});
  joints[3].channels = rot("ZYX");
  joints[4] = Joint("LeftHand", 3, {25, 0, 0});
  joints[4].channels = rot("XZY");
  joints[5] = Joint("RightLeg", 0, {-9, -5, 0});
  joints[5].channels = rot("YXZ");
  std::vector<EndSite> ends = {{"Head_End", 2, {0, 12, 0}}, {"LeftHand_End", 4, {8, 0, 0}},
                               {"RightLeg_End", 5, {0, -45, 3}}};
  Skeleton s;
  const Status status = Skeleton::Create(joints, ends, Centimetres(), &s);
  EXPECT_TRUE(status.ok()) << status.message();
  return s;
}

// Every joint moving (so that the reader takes every node as a joint), at 30 fps.
Motion TestMotion(const Skeleton& s, int frames) {
  Motion m;
  m.frame_rate = 30.0;
  for (int f = 0; f < frames; ++f) {
    Pose p = RestPose(s);
    for (int j = 0; j < s.num_joints(); ++j) {
      const Eigen::Vector3d v(0.8 * std::sin(0.2 * f + j), 0.6 * std::cos(0.13 * f * (j + 1)), 0.5 * std::sin(0.05 * f));
      p.rotations[j] = ExpMap(v);
    }
    p.translations[0] += Eigen::Vector3d(2.0 * f, 3.0 * std::sin(0.3 * f), -1.5 * f);
    m.frames.push_back(p);
  }
  return m;
}

// World positions of every joint and end site of `b` equal `a`'s, by name, in every frame,
// within `tolerance` (file units); returns the largest difference.
double CompareWorldPositions(const Skeleton& a, const Motion& ma, const Skeleton& b, const Motion& mb,
                             double tolerance) {
  EXPECT_EQ(ma.num_frames(), mb.num_frames());
  // A BVH's 0.00833333 s frame time is written as 120 fps (1e-5 of a whole rate).
  EXPECT_NEAR(ma.frame_rate, mb.frame_rate, 1e-5 * ma.frame_rate);
  FkData fa(a), fb(b);
  double worst = 0.0;
  int compared = 0;
  for (int f = 0; f < std::min(ma.num_frames(), mb.num_frames()); ++f) {
    ForwardKinematics(a, ma.frames[f], &fa);
    ForwardKinematics(b, mb.frames[f], &fb);
    const Vector3dVector ea = EndSitePositions(a, fa), eb = EndSitePositions(b, fb);
    for (int j = 0; j < b.num_joints(); ++j) {
      const int i = a.FindJoint(b.name(j));
      if (i < 0) continue;
      worst = std::max(worst, (fa.world_positions[i] - fb.world_positions[j]).norm());
      ++compared;
    }
    for (size_t e = 0; e < b.end_sites().size(); ++e) {
      for (size_t k = 0; k < a.end_sites().size(); ++k) {
        if (a.end_sites()[k].name != b.end_sites()[e].name) continue;
        worst = std::max(worst, (ea[k] - eb[e]).norm());
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 0);
  EXPECT_LT(worst, tolerance);
  return worst;
}

TEST(FbxWriter, SkeletonAndClipReadBackThroughAssimp) {
  const Skeleton skeleton = TestSkeleton();
  const Motion motion = TestMotion(skeleton, 40);
  const std::string path = testing::TempPath("clip.fbx");
  Status status = WriteFbx(path, skeleton, motion);
  ASSERT_TRUE(status.ok()) << status.message();
  Skeleton back;
  Motion back_motion;
  status = ReadMotionFile(path, {}, &back, &back_motion);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(back.num_joints(), skeleton.num_joints());
  EXPECT_EQ(back.end_sites().size(), skeleton.end_sites().size());
  EXPECT_EQ(back.unit().name, "cm");
  // 0.01 mm = 0.001 cm: float keys (7 digits) on a 2 m figure.
  const double worst = CompareWorldPositions(skeleton, motion, back, back_motion, 0.001);
  std::printf("assimp round trip: largest joint position error %.3g cm\n", worst);
}

// Key reduction (FbxWriteOptions::key_tolerance_mm): fewer keys, every joint and end site
// read back by assimp within the bound E (the shares of the animated joints above a point
// add to at most E), and a joint that never turns has no curves but reads back in place.
TEST(FbxWriter, KeyReductionStaysWithinItsBound) {
  const Skeleton skeleton = TestSkeleton();
  Motion motion = TestMotion(skeleton, 300);
  for (int f = 0; f < motion.num_frames(); ++f) {  // Slow, smooth turns (a retargeted take's), the head still.
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      motion.frames[f].rotations[j] = ExpMap(Eigen::Vector3d(0.5 * std::sin(0.02 * f + j), 0.3 * std::cos(0.015 * f),
                                                             0.2 * std::sin(0.01 * f * (j + 1))));
    }
    motion.frames[f].rotations[2] = Eigen::Quaterniond::Identity();
  }
  std::string exact, reduced;
  ASSERT_TRUE(SerializeFbx(skeleton, motion, {}, nullptr, &exact).ok());
  FbxWriteOptions options;
  options.key_tolerance_mm = 0.5;
  ASSERT_TRUE(SerializeFbx(skeleton, motion, options, nullptr, &reduced).ok());
  size_t exact_keys = 0, reduced_keys = 0, rotation_nodes = 0;
  for (const auto& [bytes, keys] : {std::pair{&exact, &exact_keys}, std::pair{&reduced, &reduced_keys}}) {
    const std::vector<FbxRecord> top = ParseFbxFile(*bytes);
    const FbxRecord* objects = Find(top, "Objects");
    ASSERT_NE(objects, nullptr);
    for (const FbxRecord& object : objects->children) {
      if (object.name == "AnimationCurveNode" && bytes == &reduced && object.properties.size() > 1 &&
          object.properties[1].text.rfind("R", 0) == 0) {
        ++rotation_nodes;
      }
      if (object.name != "AnimationCurve") continue;
      const FbxRecord* times = Find(object.children, "KeyTime");
      ASSERT_NE(times, nullptr);
      *keys += times->properties[0].numbers.size();
    }
  }
  EXPECT_EQ(rotation_nodes, static_cast<size_t>(skeleton.num_joints() - 1)) << "not the still head";
  EXPECT_LT(reduced_keys, exact_keys * 3 / 4);
  EXPECT_LT(reduced.size(), exact.size());
  const std::string path = testing::TempPath("reduced.fbx");
  ASSERT_TRUE(WriteFileAtomically(path, reduced).ok());
  Skeleton back;
  Motion back_motion;
  Status status = ReadMotionFile(path, {}, &back, &back_motion);
  ASSERT_TRUE(status.ok()) << status.message();
  // The still head (no curves) and its end site are read back too, not dropped.
  EXPECT_EQ(back.num_joints(), skeleton.num_joints());
  EXPECT_EQ(back.end_sites().size(), skeleton.end_sites().size());
  const double worst = CompareWorldPositions(skeleton, motion, back, back_motion, 0.05 + 0.001);  // cm.
  std::printf("keys %zu -> %zu at 0.5 mm: largest joint error %.3g mm\n", exact_keys, reduced_keys, 10 * worst);
}

TEST(FbxWriter, FileStructureFollowsTheFormat) {
  const Skeleton skeleton = TestSkeleton();
  const Motion motion = TestMotion(skeleton, 5);
  std::string bytes;
  ASSERT_TRUE(SerializeFbx(skeleton, motion, {}, nullptr, &bytes).ok());
  std::vector<FbxRecord> top;
  ASSERT_NO_THROW(top = ParseFbxFile(bytes));
  for (const char* name : {"FBXHeaderExtension", "FileId", "CreationTime", "GlobalSettings", "Documents",
                           "Definitions", "Objects", "Connections", "Takes"}) {
    EXPECT_NE(Find(top, name), nullptr) << name;
  }
  const FbxRecord* settings = Find(Find(top, "GlobalSettings")->children, "Properties70");
  ASSERT_NE(settings, nullptr);
  int checked = 0;
  for (const FbxRecord& p : settings->children) {
    const std::string& key = p.properties[0].text;
    const double value = p.properties.size() > 4 && !p.properties[4].numbers.empty() ? p.properties[4].numbers[0] : -1;
    if (key == "UpAxis" || key == "UnitScaleFactor" || key == "TimeMode") ++checked;
    if (key == "UpAxis") {
      EXPECT_EQ(value, 1);
    } else if (key == "UnitScaleFactor") {
      EXPECT_EQ(value, 1.0);  // cm.
    } else if (key == "TimeMode") {
      EXPECT_EQ(value, 6);  // 30 fps.
    }
  }
  EXPECT_EQ(checked, 3);
  // One LimbNode model per joint and end site, one curve node R per joint, T for the root.
  int limbs = 0, curve_nodes = 0;
  for (const FbxRecord& r : Find(top, "Objects")->children) {
    if (r.name == "Model" && r.properties[2].text == "LimbNode") ++limbs;
    if (r.name == "AnimationCurveNode") ++curve_nodes;
  }
  EXPECT_EQ(limbs, skeleton.num_joints() + static_cast<int>(skeleton.end_sites().size()));
  // RotationOrder: Hips' ZXY channels are FBX YXZ (3); Spine has a rest rotation, so
  // PreRotation and XYZ (0), which every reader evaluates alike; Head's YZX is FBX XZY (1).
  const auto model_property = [&](const std::string& model, const std::string& key) {
    for (const FbxRecord& r : Find(top, "Objects")->children) {
      if (r.name != "Model" || r.properties[1].text != model + std::string("\x00\x01Model", 7)) continue;
      for (const FbxRecord& p : Find(r.children, "Properties70")->children) {
        if (p.properties[0].text == key) return p.properties[4].numbers[0];
      }
    }
    return -1.0;
  };
  EXPECT_EQ(model_property("Hips", "RotationOrder"), 3);
  EXPECT_EQ(model_property("Spine", "RotationOrder"), 0);
  EXPECT_NE(model_property("Spine", "PreRotation"), -1.0);
  EXPECT_EQ(model_property("Head", "RotationOrder"), 1);
  EXPECT_EQ(model_property("Head", "PreRotation"), -1.0);
  EXPECT_EQ(curve_nodes, skeleton.num_joints() + 1);
}

// A joint turning three full times about its y axis (and wobbling about x), the root
// turning backwards twice about z: the keys are unrolled, no jump between frames, and the
// file reads back to the same poses.
TEST(FbxWriter, FullTurnsGiveContinuousEulerCurves) {
  const Skeleton skeleton = TestSkeleton();
  Motion motion = TestMotion(skeleton, 91);
  for (int f = 0; f < motion.num_frames(); ++f) {
    const double s = f / 90.0;
    for (int j = 1; j < skeleton.num_joints(); ++j) {  // Slow enough for < 20 degrees a frame.
      motion.frames[f].rotations[j] = ExpMap(Eigen::Vector3d(0.5 * std::sin(3 * s + j), 0.4 * std::cos(2 * s * j), 0.2));
    }
    motion.frames[f].rotations[0] = Eigen::Quaterniond(Eigen::AngleAxisd(-4 * kPi * s, Eigen::Vector3d::UnitZ()));
    motion.frames[f].rotations[2] = Eigen::Quaterniond(Eigen::AngleAxisd(6 * kPi * s, Eigen::Vector3d::UnitY()) *
                                                       Eigen::AngleAxisd(0.3 * std::sin(9 * s), Eigen::Vector3d::UnitX()));
  }
  std::string bytes;
  ASSERT_TRUE(SerializeFbx(skeleton, motion, {}, nullptr, &bytes).ok());
  std::vector<FbxRecord> top;
  ASSERT_NO_THROW(top = ParseFbxFile(bytes));
  double largest_step = 0.0, largest_angle = 0.0;
  int curves = 0;
  for (const FbxRecord& r : Find(top, "Objects")->children) {
    if (r.name != "AnimationCurve") continue;
    const std::vector<double>& v = Find(r.children, "KeyValueFloat")->properties[0].numbers;
    const std::vector<double>& t = Find(r.children, "KeyTime")->properties[0].numbers;
    ASSERT_EQ(t.size(), v.size());
    // Per frame: a key may stand for a run the line between its neighbours reproduces.
    for (size_t k = 1; k < v.size(); ++k) {
      const double frames = (t[k] - t[k - 1]) / (46186158000.0 / 30.0);
      largest_step = std::max(largest_step, std::abs(v[k] - v[k - 1]) / frames);
    }
    for (double a : v) largest_angle = std::max(largest_angle, std::abs(a));
    ++curves;
  }
  EXPECT_GT(curves, 0);
  // 3 turns in 90 frames is 12 degrees a frame; the other joints move less.
  EXPECT_LT(largest_step, 20.0);
  EXPECT_GT(largest_angle, 1000.0);  // Unrolled: the head ends near 1080 degrees.
  const std::string path = testing::TempPath("turns.fbx");
  ASSERT_TRUE(WriteFileAtomically(path, bytes).ok());
  Skeleton back;
  Motion back_motion;
  const Status status = ReadMotionFile(path, {}, &back, &back_motion);
  ASSERT_TRUE(status.ok()) << status.message();
  CompareWorldPositions(skeleton, motion, back, back_motion, 0.001);
}

TEST(FbxWriter, NameWithNulIsAnErrorNamingTheJointAndNothingIsWritten) {
  std::vector<JointSpec> joints(2);
  joints[0] = Joint("Hips", -1, {0, 1, 0});
  joints[1] = Joint(std::string("Left\0Arm", 8), 0, {1, 0, 0});
  Skeleton skeleton;
  ASSERT_TRUE(Skeleton::Create(joints, {}, Metres(), &skeleton).ok());
  Motion motion;
  motion.frame_rate = 30;
  motion.frames.push_back(RestPose(skeleton));
  const std::string path = testing::TempPath("bad.fbx");
  const Status status = WriteFbx(path, skeleton, motion);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("joint 1 'Left\\x00Arm'"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("NUL"), std::string::npos) << status.message();
  EXPECT_FALSE(testing::FileExists(path));
}

// A chain of `n` joints, each 1 cm above its parent.
Skeleton Chain(int n) {
  std::vector<JointSpec> joints(n);
  for (int j = 0; j < n; ++j) joints[j] = Joint("j" + std::to_string(j), j - 1, {0, j == 0 ? 0.0 : 0.01, 0});
  Skeleton skeleton;
  EXPECT_TRUE(Skeleton::Create(joints, {}, Metres(), &skeleton).ok());
  return skeleton;
}

TEST(FbxWriter, SkeletonDeeperThanImportersReadIsAnErrorNamingTheJoint) {
  Motion motion;
  motion.frame_rate = 30;
  const Skeleton deepest = Chain(kMaxFbxSkeletonDepth + 1);  // Its last joint is kMaxFbxSkeletonDepth below the root.
  motion.frames.assign(1, RestPose(deepest));
  std::string bytes;
  EXPECT_TRUE(SerializeFbx(deepest, motion, {}, nullptr, &bytes).ok());
  const Skeleton too_deep = Chain(kMaxFbxSkeletonDepth + 2);
  motion.frames.assign(1, RestPose(too_deep));
  const std::string path = testing::TempPath("deep.fbx");
  const Status status = WriteFbx(path, too_deep, motion);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("joint 901 'j901': 901 levels below the root, deeper than the 900"),
            std::string::npos) << status.message();
  EXPECT_FALSE(testing::FileExists(path));
}

TEST(FbxWriter, EmptyMotionAndBadRateAreErrors) {
  const Skeleton skeleton = TestSkeleton();
  Motion motion;
  motion.frame_rate = 30;
  std::string bytes;
  EXPECT_FALSE(SerializeFbx(skeleton, motion, {}, nullptr, &bytes).ok());
  motion = TestMotion(skeleton, 3);
  motion.frame_rate = 0;
  EXPECT_FALSE(SerializeFbx(skeleton, motion, {}, nullptr, &bytes).ok());
}

// A tiny skinned mesh: a strip of 8 vertices along the arm, weighted between joints.
TEST(FbxWriter, SkinnedMeshReadsBackThroughAssimp) {
  const Skeleton skeleton = TestSkeleton();
  const Motion motion = TestMotion(skeleton, 10);
  FkData bind(skeleton);
  ForwardKinematics(skeleton, RestPose(skeleton), &bind);
  SkinnedMeshSpec spec;
  spec.rest_positions.resize(3, 8);
  spec.rest_normals.resize(3, 8);
  for (int i = 0; i < 8; ++i) {
    spec.rest_positions.col(i) = Eigen::Vector3d(15.0 + 5.0 * (i / 2), 115.0 + 2.0 * (i % 2), 1.0);
    spec.rest_normals.col(i) = Eigen::Vector3d(0, 0, 1);
    const double w = (i / 2) / 3.0;
    spec.influences.push_back({{3, 1.0 - w}, {4, w}});
  }
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    Eigen::Isometry3d world = Eigen::Isometry3d::Identity();
    world.linear() = bind.world_rotations[j].toRotationMatrix();
    world.translation() = bind.world_positions[j];
    spec.joint_from_bind.push_back(world.inverse());
  }
  SkinnedMesh mesh;
  ASSERT_TRUE(SkinnedMesh::Create(skeleton, spec, &mesh).ok());
  Eigen::Matrix3Xi triangles(3, 6);
  for (int q = 0; q < 3; ++q) {
    triangles.col(2 * q) << 2 * q, 2 * q + 2, 2 * q + 1;
    triangles.col(2 * q + 1) << 2 * q + 1, 2 * q + 2, 2 * q + 3;
  }
  FbxSkinnedMesh input{&mesh, &triangles, "strip"};
  const std::string path = testing::TempPath("skinned.fbx");
  Status status = WriteFbx(path, skeleton, motion, {}, &input);
  ASSERT_TRUE(status.ok()) << status.message();
  Skeleton back;
  Motion back_motion;
  FbxInfo info;
  status = ReadFbx(path, {}, &back, &back_motion, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  CompareWorldPositions(skeleton, motion, back, back_motion, 0.001);
  EXPECT_EQ(info.skinned_meshes, 1);
  EXPECT_EQ(info.bones, skeleton.num_joints());  // One cluster per joint (weights on 2 of them).
  // assimp makes one vertex per polygon corner; each is a rest position of the strip.
  ASSERT_EQ(info.vertices, 18);
  ASSERT_EQ(info.mesh_vertices.cols(), 18);
  for (int c = 0; c < 18; ++c) {
    const Eigen::Vector3d expected = mesh.rest_positions().col(triangles(c % 3, c / 3));
    EXPECT_LT((info.mesh_vertices.col(c) - expected).norm(), 1e-4) << c;
  }
}

// The converter from a BVH: `mocapsolve convert IN.bvh OUT.fbx` reads back to the BVH's
// joint positions.
TEST(FbxWriter, ConvertWritesFbxFromBvh) {
  MOCAPSOLVE_DATA_FILE(bvh, "bvh/16_15.bvh");
  const std::string out = testing::TempPath("16_15.fbx");
  std::string output;
  ASSERT_EQ(testing::RunCli("convert '" + bvh + "' '" + out + "' --quiet", &output), 0) << output;
  Skeleton a, b;
  Motion ma, mb;
  ASSERT_TRUE(ReadMotionFile(bvh, {}, &a, &ma).ok());
  const Status status = ReadMotionFile(out, {}, &b, &mb);
  ASSERT_TRUE(status.ok()) << status.message();
  // CMU units (~0.056 m): 0.01 mm is 2e-4 units.
  const double worst = CompareWorldPositions(a, ma, b, mb, 2e-4);
  std::printf("16_15 via convert: largest joint position error %.3g units\n", worst);
}

// Xbot with its own first clip and its mesh: assimp reads the joints back to the same
// world positions (metres), the mesh with every triangle corner. Prints the size beside
// the GLB of the same content.
TEST(FbxWriter, XbotCharacterRoundTrip) {
  MOCAPSOLVE_DATA_FILE(path, "gltf/Xbot.glb");
  GltfDocument document;
  ASSERT_TRUE(GltfDocument::Read(path, &document).ok());
  GltfCharacter character;
  ASSERT_TRUE(ReadGltfCharacter(document, {}, &character).ok());
  Motion motion;
  GltfAnimationOptions animation;
  animation.animation = character.animation_names.size() > 1 ? "1" : "0";
  ASSERT_TRUE(ReadGltfAnimation(document, character, animation, &motion).ok());
  const std::string out = testing::TempPath("xbot.fbx");
  Status status = WriteFbxCharacter(out, character, motion, "clip", false);
  ASSERT_TRUE(status.ok()) << status.message();
  Skeleton back;
  Motion back_motion;
  FbxInfo info;
  status = ReadFbx(out, {}, &back, &back_motion, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(info.vertices, 3 * character.triangles.cols());
  EXPECT_GT(back.num_joints(), 10);
  // 1e-5 m = 0.01 mm.
  const double worst = CompareWorldPositions(character.skeleton, motion, back, back_motion, 1e-5);
  const std::string glb = testing::TempPath("xbot.glb");
  ASSERT_TRUE(WriteGltfWithAnimation(document, character, motion, "mocapsolve clip", glb).ok());
  const std::string fbx_bytes = testing::ReadTextFile(out), glb_bytes = testing::ReadTextFile(glb);
  std::printf("Xbot (%d joints read back, %d frames): largest joint error %.3g m; FBX %zu bytes, GLB %zu bytes\n",
              back.num_joints(), motion.num_frames(), worst, fbx_bytes.size(), glb_bytes.size());
  const std::string anim_only = testing::TempPath("xbot_anim.fbx");
  ASSERT_TRUE(WriteFbxCharacter(anim_only, character, motion, "clip", true).ok());
  status = ReadFbx(anim_only, {}, &back, &back_motion, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(info.meshes, 0);
  CompareWorldPositions(character.skeleton, motion, back, back_motion, 1e-5);
}

// The encoder hands a sink the bytes it would return whole, in order, in pieces of about a
// megabyte (a long take's file written straight to disk), and the sink's first error ends it.
TEST(FbxBinary, SinkGetsTheWholeBytesInPieces) {
  fbx::Node objects("Objects");
  std::vector<float> noise(3'000'000);  // Incompressible enough to stay megabytes.
  uint32_t state = 1;
  for (float& v : noise) v = static_cast<float>((state = state * 1664525u + 1013904223u) >> 8);
  objects.AddChild("AnimationCurve").Int64(7).FloatArray(noise);
  objects.AddChild("AnimationStack").Int64(8);
  fbx::Node takes("Takes");
  takes.AddChild("Current").String("clip");
  const std::vector<const fbx::Node*> top = {&objects, &takes};
  std::string whole;
  ASSERT_TRUE(fbx::EncodeFbxBinary(top, &whole).ok());
  std::string joined;
  int pieces = 0;
  ASSERT_TRUE(fbx::EncodeFbxBinary(top, [&](std::string_view piece) {
                ++pieces;
                EXPECT_LE(piece.size(), 13u << 20);
                joined.append(piece);
                return Status::Ok();
              }).ok());
  EXPECT_EQ(joined, whole);
  EXPECT_GT(pieces, 2);
  int calls = 0;
  const Status failed = fbx::EncodeFbxBinary(top, [&](std::string_view) {
    ++calls;
    return Status::Error("disk full");
  });
  EXPECT_FALSE(failed.ok());
  EXPECT_EQ(failed.message(), "disk full");
  EXPECT_EQ(calls, 1);
}

// A character's take written from its CompactMotion (a windowed pipeline's long take, read
// one joint of one frame at a time) is the file written from the same take expanded.
TEST(FbxWriter, CharacterFromACompactTakeIsTheBytesOfItsExpandedTake) {
  const std::string gltf = testing::TempPath("compact_character.gltf");
  testing::WriteTestCharacter(gltf, 45.0);
  GltfDocument document;
  ASSERT_TRUE(GltfDocument::Read(gltf, &document).ok());
  GltfCharacter character;
  ASSERT_TRUE(ReadGltfCharacter(document, {}, &character).ok());
  Motion motion;
  motion.frame_rate = 120.0;
  for (int f = 0; f < 50; ++f) {
    Pose pose = character.rest_pose;
    pose.translations[0] += Eigen::Vector3d(0.01 * f, 0.0, 0.002 * f);
    for (int j = 0; j < character.skeleton.num_joints(); ++j) {
      pose.rotations[j] = pose.rotations[j] * Eigen::Quaterniond(Eigen::AngleAxisd(0.03 * f * (j % 3 + 1),
                                                                                    Eigen::Vector3d(0.3, 1.0, 0.2).normalized()));
    }
    motion.frames.push_back(pose);
  }
  const CompactMotion compact(motion);
  for (bool animation_only : {false, true}) {
    const std::string from_compact = testing::TempPath("from_compact.fbx"), expanded = testing::TempPath("expanded.fbx");
    ASSERT_TRUE(WriteFbxCharacter(from_compact, character, compact, "clip", animation_only).ok());
    ASSERT_TRUE(WriteFbxCharacter(expanded, character, compact.ToMotion(), "clip", animation_only).ok());
    const std::string bytes = testing::ReadTextFile(from_compact);
    EXPECT_GT(bytes.size(), 1000u);
    EXPECT_TRUE(bytes == testing::ReadTextFile(expanded)) << "animation_only " << animation_only;
  }
}

}  // namespace
}  // namespace mocapsolve
