#include "tests/gltf_test_files.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "io/gltf_reader.h"
#include "tests/test_support.h"
#include "viewer/view_page.h"

namespace mocapsolve::testing {
namespace {

// Images are written by WriteGltfVariant itself: tinygltf keeps each image's `uri`.
bool KeepImageUri(const std::string*, const std::string*, const tinygltf::Image*, bool, std::string*, void*) {
  return false;
}

}  // namespace

void WriteGltfVariant(const std::string& source, const std::string& gltf_path, GltfLayout layout) {
  GltfDocument document;  // Keeps every image's encoded bytes (gltf_reader.h).
  const Status status = GltfDocument::Read(source, &document);
  ASSERT_TRUE(status.ok()) << status.message();
  tinygltf::Model model = document.model();
  const size_t slash = gltf_path.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : gltf_path.substr(0, slash);
  std::string stem = gltf_path.substr(slash == std::string::npos ? 0 : slash + 1);
  stem = stem.substr(0, stem.rfind('.'));
  const bool files = layout == GltfLayout::kSeparateFiles;
  for (size_t i = 0; i < model.images.size(); ++i) {
    tinygltf::Image& image = model.images[i];
    ASSERT_FALSE(image.image.empty()) << source << ": image " << i << " has no bytes";
    const bool jpeg = image.image.size() > 2 && image.image[0] == 0xff && image.image[1] == 0xd8;
    const std::string bytes(image.image.begin(), image.image.end());
    if (files) {
      image.uri = stem + "_image" + std::to_string(i) + (jpeg ? ".jpg" : ".png");
      WriteTextFile(dir + "/" + image.uri, bytes);
    } else {
      image.uri = std::string("data:image/") + (jpeg ? "jpeg" : "png") + ";base64," + Base64(bytes);
    }
    image.bufferView = -1;
    image.mimeType.clear();
    image.image.clear();
  }
  for (size_t b = 0; b < model.buffers.size(); ++b) {
    model.buffers[b].uri = files ? stem + (b == 0 ? "" : std::to_string(b)) + ".bin" : "";
  }
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(&KeepImageUri, nullptr);
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&model, gltf_path, /*embedImages=*/false, /*embedBuffers=*/!files,
                                          /*prettyPrint=*/true, /*writeBinary=*/false))
      << gltf_path << ": tinygltf could not write it";
}

std::vector<TestCharacterJoint> TestCharacterJoints(double arm_degrees_below_horizontal) {
  const double a = arm_degrees_below_horizontal * 3.14159265358979323846 / 180.0;
  const double c = std::cos(a), s = std::sin(a);
  return {
      {"Hips", -1, 0, 0.95, 0},      {"Spine", 0, 0, 0.15, 0},          {"Spine1", 1, 0, 0.2, 0},
      {"Neck", 2, 0, 0.2, 0},        {"Head", 3, 0, 0.1, 0},            {"LeftShoulder", 2, 0.05, 0.15, 0},
      {"LeftArm", 5, 0.1, 0, 0},     {"LeftForeArm", 6, 0.28 * c, -0.28 * s, 0},
      {"LeftHand", 7, 0.25 * c, -0.25 * s, 0},                          {"RightShoulder", 2, -0.05, 0.15, 0},
      {"RightArm", 9, -0.1, 0, 0},   {"RightForeArm", 10, -0.28 * c, -0.28 * s, 0},
      {"RightHand", 11, -0.25 * c, -0.25 * s, 0},                       {"LeftUpLeg", 0, 0.1, -0.05, 0},
      {"LeftLeg", 13, 0, -0.42, 0},  {"LeftFoot", 14, 0, -0.43, 0},     {"RightUpLeg", 0, -0.1, -0.05, 0},
      {"RightLeg", 16, 0, -0.42, 0}, {"RightFoot", 17, 0, -0.43, 0},
  };
}

namespace {

// The test humanoid's joints in the world (metres), and its mesh: one vertex per joint,
// one at the head's top, one at the left sole; vertex_joint: the joint each follows.
void TestCharacterMesh(const std::vector<TestCharacterJoint>& joints, std::vector<Eigen::Vector3d>* world,
                       std::vector<Eigen::Vector3d>* vertices, std::vector<int>* vertex_joint) {
  const int n = static_cast<int>(joints.size());
  world->assign(n, Eigen::Vector3d::Zero());
  for (int j = 0; j < n; ++j) {
    (*world)[j] = Eigen::Vector3d(joints[j].x, joints[j].y, joints[j].z) +
                  (joints[j].parent >= 0 ? (*world)[joints[j].parent] : Eigen::Vector3d::Zero());
  }
  *vertices = *world;
  vertex_joint->clear();
  for (int j = 0; j < n; ++j) vertex_joint->push_back(j);
  vertices->push_back((*world)[4] + Eigen::Vector3d(0, 0.15, 0)), vertex_joint->push_back(4);
  vertices->push_back((*world)[15] + Eigen::Vector3d(0, -0.05, 0.05)), vertex_joint->push_back(15);
}

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.9g", v);
  return text;
}

}  // namespace

void WriteTestCharacterFbx(const std::string& fbx_path, double arm_degrees_below_horizontal) {
  const std::vector<TestCharacterJoint> joints = TestCharacterJoints(arm_degrees_below_horizontal);
  std::vector<Eigen::Vector3d> world, vertices;
  std::vector<int> vertex_joint;
  TestCharacterMesh(joints, &world, &vertices, &vertex_joint);
  const int n = static_cast<int>(joints.size()), nv = static_cast<int>(vertices.size());
  std::string points, polygons, objects, connections;
  for (int v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) points += (v || k ? "," : "") + Number(100.0 * vertices[v][k]);
    polygons += (v ? "," : "") + std::to_string(v % 3 == 2 ? -v - 1 : v);
  }
  objects += "\tGeometry: 2000, \"Geometry::Body\", \"Mesh\" {\n\t\tVertices: *" + std::to_string(3 * nv) +
             " {\n\t\t\ta: " + points + "\n\t\t}\n\t\tPolygonVertexIndex: *" + std::to_string(nv) + " {\n\t\t\ta: " +
             polygons + "\n\t\t}\n\t\tGeometryVersion: 124\n\t}\n";
  objects += "\tModel: 2001, \"Model::Body\", \"Mesh\" {\n\t\tVersion: 232\n\t}\n";
  objects += "\tDeformer: 3000, \"Deformer::Skin\", \"Skin\" {\n\t\tVersion: 101\n\t}\n";
  connections += "\tC: \"OO\",2001,0\n\tC: \"OO\",2000,2001\n\tC: \"OO\",3000,2000\n";
  const std::string identity = "1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1";
  for (int j = 0; j < n; ++j) {
    const int model = 1000 + j, cluster = 3001 + j;
    objects += "\tModel: " + std::to_string(model) + ", \"Model::" + joints[j].name + "\", \"LimbNode\" {\n"
               "\t\tVersion: 232\n\t\tProperties70:  {\n\t\t\tP: \"Lcl Translation\", \"Lcl Translation\", \"\", \"A\"," +
               Number(100.0 * joints[j].x) + "," + Number(100.0 * joints[j].y) + "," + Number(100.0 * joints[j].z) +
               "\n\t\t}\n\t}\n";
    std::string indexes;
    for (int v = 0; v < nv; ++v) {
      if (vertex_joint[v] == j) indexes += (indexes.empty() ? "" : ",") + std::to_string(v);
    }
    const int count = static_cast<int>(std::count(vertex_joint.begin(), vertex_joint.end(), j));
    std::string weights;
    for (int k = 0; k < count; ++k) weights += k ? ",1" : "1";
    const std::string link = "1,0,0,0,0,1,0,0,0,0,1,0," + Number(100.0 * world[j].x()) + "," +
                             Number(100.0 * world[j].y()) + "," + Number(100.0 * world[j].z()) + ",1";
    objects += "\tDeformer: " + std::to_string(cluster) + ", \"SubDeformer::" + joints[j].name + "\", \"Cluster\" {\n"
               "\t\tVersion: 100\n\t\tIndexes: *" + std::to_string(count) + " {\n\t\t\ta: " + indexes + "\n\t\t}\n"
               "\t\tWeights: *" + std::to_string(count) + " {\n\t\t\ta: " + weights + "\n\t\t}\n"
               "\t\tTransform: *16 {\n\t\t\ta: " + identity + "\n\t\t}\n"
               "\t\tTransformLink: *16 {\n\t\t\ta: " + link + "\n\t\t}\n\t}\n";
    connections += "\tC: \"OO\"," + std::to_string(model) + "," +
                   std::to_string(joints[j].parent < 0 ? 0 : 1000 + joints[j].parent) + "\n";
    connections += "\tC: \"OO\"," + std::to_string(cluster) + ",3000\n\tC: \"OO\"," + std::to_string(model) + "," +
                   std::to_string(cluster) + "\n";
  }
  WriteTextFile(fbx_path, "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n\tFBXHeaderVersion: 1003\n"
                          "\tFBXVersion: 7400\n}\nGlobalSettings:  {\n\tVersion: 1000\n\tProperties70:  {\n"
                          "\t\tP: \"UnitScaleFactor\", \"double\", \"Number\", \"\",1\n\t}\n}\nObjects:  {\n" +
                          objects + "}\nConnections:  {\n" + connections + "}\n");
}

void WriteTestCharacter(const std::string& gltf_path, double arm_degrees_below_horizontal) {
  const std::vector<TestCharacterJoint> joints = TestCharacterJoints(arm_degrees_below_horizontal);
  std::vector<Eigen::Vector3d> world, vertices;
  std::vector<int> vertex_joint;
  TestCharacterMesh(joints, &world, &vertices, &vertex_joint);
  const int n = static_cast<int>(joints.size());
  std::vector<float> floats;  // Inverse bind matrices (column-major), then positions, then weights.
  for (int j = 0; j < n; ++j) {
    const float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, static_cast<float>(-world[j].x()),
                         static_cast<float>(-world[j].y()), static_cast<float>(-world[j].z()), 1};
    floats.insert(floats.end(), m, m + 16);
  }
  const int nv = static_cast<int>(vertices.size());
  Eigen::Vector3d lo = vertices[0], hi = vertices[0];
  for (const Eigen::Vector3d& v : vertices) {
    lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    for (int k = 0; k < 3; ++k) floats.push_back(static_cast<float>(v[k]));
  }
  for (int v = 0; v < nv; ++v) floats.insert(floats.end(), {1.0f, 0.0f, 0.0f, 0.0f});
  std::string bytes(reinterpret_cast<const char*>(floats.data()), floats.size() * sizeof(float));
  for (int v = 0; v < nv; ++v) bytes += std::string{static_cast<char>(vertex_joint[v]), 0, 0, 0};
  const size_t ibm_bytes = 64 * n, position_bytes = 12 * nv, weight_bytes = 16 * nv, joint_bytes = 4 * nv;
  std::string nodes, skin_joints;
  for (int j = 0; j < n; ++j) {
    std::string children;
    for (int k = 0; k < n; ++k) {
      if (joints[k].parent == j) children += (children.empty() ? "" : ",") + std::to_string(k);
    }
    nodes += std::string(j ? ",\n" : "") + "{\"name\": \"" + joints[j].name + "\", \"translation\": [" +
             Number(joints[j].x) + ", " + Number(joints[j].y) + ", " + Number(joints[j].z) + "]" +
             (children.empty() ? "" : ", \"children\": [" + children + "]") + "}";
    skin_joints += (j ? "," : "") + std::to_string(j);
  }
  nodes += ",\n{\"name\": \"Body\", \"mesh\": 0, \"skin\": 0}";
  const std::string json =
      "{\"asset\": {\"version\": \"2.0\", \"generator\": \"mocapsolve tests (WriteTestCharacter)\"},\n"
      "\"scene\": 0, \"scenes\": [{\"nodes\": [0, " + std::to_string(n) + "]}],\n\"nodes\": [" + nodes + "],\n"
      "\"skins\": [{\"name\": \"body\", \"joints\": [" + skin_joints + "], \"inverseBindMatrices\": 0}],\n"
      "\"meshes\": [{\"name\": \"body\", \"primitives\": [{\"attributes\": {\"POSITION\": 1, \"JOINTS_0\": 3, "
      "\"WEIGHTS_0\": 2}}]}],\n"
      "\"buffers\": [{\"byteLength\": " + std::to_string(bytes.size()) +
      ", \"uri\": \"data:application/octet-stream;base64," + Base64(bytes) + "\"}],\n"
      "\"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": " + std::to_string(ibm_bytes) + "},\n"
      "  {\"buffer\": 0, \"byteOffset\": " + std::to_string(ibm_bytes) + ", \"byteLength\": " + std::to_string(position_bytes) + "},\n"
      "  {\"buffer\": 0, \"byteOffset\": " + std::to_string(ibm_bytes + position_bytes) + ", \"byteLength\": " +
      std::to_string(weight_bytes) + "},\n"
      "  {\"buffer\": 0, \"byteOffset\": " + std::to_string(ibm_bytes + position_bytes + weight_bytes) +
      ", \"byteLength\": " + std::to_string(joint_bytes) + "}],\n"
      "\"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": " + std::to_string(n) + ", \"type\": \"MAT4\"},\n"
      "  {\"bufferView\": 1, \"componentType\": 5126, \"count\": " + std::to_string(nv) + ", \"type\": \"VEC3\", \"min\": [" +
      Number(lo.x()) + ", " + Number(lo.y()) + ", " + Number(lo.z()) + "], \"max\": [" + Number(hi.x()) + ", " +
      Number(hi.y()) + ", " + Number(hi.z()) + "]},\n"
      "  {\"bufferView\": 2, \"componentType\": 5126, \"count\": " + std::to_string(nv) + ", \"type\": \"VEC4\"},\n"
      "  {\"bufferView\": 3, \"componentType\": 5121, \"count\": " + std::to_string(nv) + ", \"type\": \"VEC4\"}]}\n";
  WriteTextFile(gltf_path, json);
}

}  // namespace mocapsolve::testing
