// `info` as one function: what a marker (C3D, TRC), motion (BVH, ASF+AMC, FBX, glTF),
// skeleton (ASF) or character (glTF/GLB, FBX) file holds, read and counted: labels,
// frames, gaps; meshes, skins, the skeleton's first levels, its height and bind-pose kind
// (kinematics/bind_pose_shape.h); the animations and the root's path. The CLI
// (apps/info_command.cc: prints the result) and Python's info() (the report as a dict)
// both call it.
#ifndef MOCAPSOLVE_TASKS_INFO_TASK_H_
#define MOCAPSOLVE_TASKS_INFO_TASK_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/json_writer.h"
#include "kinematics/bind_pose_shape.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "kinematics/units.h"

namespace mocapsolve {

// How motions are read (the CLI's --skeleton, --skeleton_units, --amc_fps, --animation,
// --sample_fps; read_motion's keywords). Marker files are read with the default
// MarkerReadOptions (io/marker_file.h).
struct InfoConfig {
  std::string skeleton;        // An .amc's .asf.
  std::string skeleton_units;  // A skeleton that states no unit (BVH): mm, cm, m, in.
  double amc_fps = 120.0;
  std::string animation;       // glTF/FBX clip (name or index; "" = the first).
  double sample_fps = 0.0;     // glTF/FBX sampling rate (0 = the file's).
};

// Which reader the file went to (by extension): each fills the parts named below.
enum class InfoKind {
  kMarkers,    // .c3d/.trc: markers.
  kCharacter,  // .glb/.gltf: counts; with a skin, skeleton; animations; motion if any.
  kFbx,        // .fbx: counts, skeleton, animations; motion if any.
  kSkeleton,   // .asf: skeleton (rest pose).
  kMotion,     // .bvh, .amc: skeleton (rest pose), animations if any, motion.
};

struct InfoMarkers {
  std::vector<std::string> labels;
  bool has_model_outputs = false;          // C3D model outputs (angles, forces), not markers:
  std::vector<std::string> model_outputs;  // their labels.
  int frames = 0, first_frame = 0;
  double frame_rate = 0.0, duration_s = 0.0;
  std::string units;
  int missing = 0, samples = 0, gap_runs = 0;  // Missing of frames x markers; maximal runs.
};

// The skeleton in its bind (character) or rest (motion, skeleton file) pose.
struct InfoSkeleton {
  int joints = 0, end_sites = 0;
  std::string root;
  std::vector<std::vector<std::string>> levels;  // Joint names by depth: [0] = {root}, [1], [2].
  LengthUnit unit;
  BindPoseShape shape;
};

struct InfoMotion {
  int frames = 0;
  double frame_rate = 0.0, duration_s = 0.0;
  Eigen::Vector3d root_min = Eigen::Vector3d::Zero(), root_max = Eigen::Vector3d::Zero();  // The root's path.
};

struct InfoResult {
  InfoKind kind = InfoKind::kMotion;
  std::string path;
  std::vector<std::string> warnings;  // The readers' (approximations, ignored channels).
  InfoMarkers markers;
  // Characters (glTF: every count; FBX: meshes, skinned_meshes, vertices, bones).
  int meshes = 0, skinned_meshes = 0, primitives = 0, nodes = 0, skins = 0, bones = 0;
  long long vertices = 0;
  std::string skin_name;      // glTF skin 0's ("" if unnamed).
  int skinned_vertices = 0;   // glTF skin 0's mesh.
  bool has_skeleton = false;  // All but markers and glTF files without a skin.
  InfoSkeleton skeleton;
  std::vector<std::string> animations;  // glTF/FBX clips.
  bool has_motion = false;
  InfoMotion motion;
  JsonObject report;  // What --report records.
};

// Errors name the file (or --animation: a clip the file lacks).
Status RunInfo(const std::string& path, const InfoConfig& config, InfoResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_INFO_TASK_H_
