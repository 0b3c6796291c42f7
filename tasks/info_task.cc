#include "tasks/info_task.h"

#include <limits>

#include "io/fbx_reader.h"
#include "io/gltf_contents.h"
#include "io/gltf_reader.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "kinematics/motion.h"
#include "signal/gap_fill.h"

namespace mocapsolve {
namespace {

// Marker files: labels, frames, rate, unit and gaps.
Status MarkerInfo(const std::string& path, InfoResult* r) {
  MarkerTrajectories markers;
  Status status = ReadMarkerFile(path, &markers);
  if (!status.ok()) return status;
  InfoMarkers& m = r->markers;
  m.labels = markers.labels();
  if (markers.model_outputs != nullptr) {
    m.has_model_outputs = true;
    m.model_outputs = markers.model_outputs->points.labels();
  }
  m.frames = markers.num_frames();
  m.first_frame = markers.first_frame;
  m.frame_rate = markers.frame_rate;
  m.duration_s = markers.frame_rate > 0 && m.frames > 0 ? (m.frames - 1) / markers.frame_rate : 0.0;
  m.units = markers.unit.name;
  m.missing = markers.CountMissing();
  m.samples = m.frames * markers.num_markers();
  m.gap_runs = static_cast<int>(FindGaps(markers).size());
  r->report.Add("file", path).Add("markers", markers.num_markers()).Add("frames", m.frames)
      .Add("frame_rate", m.frame_rate).Add("units", m.units)
      .Add("missing_samples", m.missing).Add("gap_runs", m.gap_runs);
  return Status::Ok();
}

// Joint names by depth below the root: levels[0] = {root}, levels[1] = its children, ...
std::vector<std::vector<std::string>> JointLevels(const Skeleton& skeleton, int depth) {
  std::vector<int> level(skeleton.num_joints(), 0);
  std::vector<std::vector<std::string>> levels(1);
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    if (j > 0) level[j] = level[skeleton.parent(j)] + 1;
    if (level[j] > depth) continue;
    if (level[j] >= static_cast<int>(levels.size())) levels.resize(level[j] + 1);
    levels[level[j]].push_back(skeleton.name(j));
  }
  return levels;
}

// The skeleton and its bind pose: joints by level, height, T-/A-pose. `vertices`: the
// bind-pose mesh (may be empty).
void DescribeSkeleton(const Skeleton& skeleton, const Pose& bind_pose, const Eigen::Matrix3Xd& vertices,
                      InfoResult* r) {
  InfoSkeleton& s = r->skeleton;
  r->has_skeleton = true;
  s.joints = skeleton.num_joints();
  s.end_sites = static_cast<int>(skeleton.end_sites().size());
  s.root = skeleton.name(0);
  s.levels = JointLevels(skeleton, 2);
  s.unit = skeleton.unit();
  s.shape = DescribeBindPose(skeleton, bind_pose, vertices);
  std::string levels_json = "[";
  for (size_t d = 0; d < s.levels.size(); ++d) {
    levels_json += d ? ", [" : "[";
    for (size_t k = 0; k < s.levels[d].size(); ++k) levels_json += (k ? ", " : "") + JsonQuote(s.levels[d][k]);
    levels_json += "]";
  }
  levels_json += "]";
  const BindPoseShape& shape = s.shape;
  const char* axis = shape.up_axis == 0 ? "X" : shape.up_axis == 1 ? "Y" : "Z";
  r->report.Add("joints", s.joints)
      .Add("end_sites", s.end_sites)
      .Add("root", s.root)
      .Add("joint_levels", JsonValue::Raw(levels_json))
      .Add("units", s.unit.name)
      .Add("metres_per_unit", s.unit.metres_per_unit)
      .Add("height", shape.height)
      .Add("height_m", s.unit.known() ? JsonValue(shape.height * s.unit.metres_per_unit) : JsonValue())
      .Add("height_from", shape.height_from_mesh ? "mesh" : "joints")
      .Add("up_axis", std::string(shape.up_sign > 0 ? "+" : "-") + axis)
      .Add("bind_pose", shape.kind);
  if (!shape.upper_arms[0].empty()) {
    r->report.Add("upper_arms", std::vector<JsonValue>{shape.upper_arms[0], shape.upper_arms[1]})
        .Add("upper_arms_below_horizontal_deg",
             std::vector<JsonValue>{shape.below_horizontal_deg[0], shape.below_horizontal_deg[1]});
  }
}

void DescribeAnimations(const std::vector<std::string>& clips, InfoResult* r) {
  r->animations = clips;
  r->report.Add("animations", std::vector<JsonValue>(clips.begin(), clips.end()));
}

// Frames, rate, duration and the root's path of one motion.
void DescribeMotion(const Motion& motion, InfoResult* r) {
  InfoMotion& m = r->motion;
  r->has_motion = true;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Pose& pose : motion.frames) {
    lo = lo.cwiseMin(pose.translations[0]);
    hi = hi.cwiseMax(pose.translations[0]);
  }
  if (motion.frames.empty()) lo = hi = Eigen::Vector3d::Zero();
  m.frames = motion.num_frames();
  m.frame_rate = motion.frame_rate;
  m.duration_s = motion.duration_seconds();
  m.root_min = lo;
  m.root_max = hi;
  r->report.Add("frames", m.frames)
      .Add("frame_rate", m.frame_rate)
      .Add("duration_s", m.duration_s)
      .Add("root_min", std::vector<JsonValue>{lo.x(), lo.y(), lo.z()})
      .Add("root_max", std::vector<JsonValue>{hi.x(), hi.y(), hi.z()});
}

// ReadMotionFile with the config's options (warnings kept, skeleton units applied).
Status ReadInfoMotion(const std::string& path, const InfoConfig& config, Skeleton* skeleton, Motion* motion,
                  InfoResult* r) {
  MotionFileOptions options;
  options.skeleton_path = config.skeleton;
  options.amc_frame_rate = config.amc_fps;
  options.animation = config.animation;  // An error for formats with one clip.
  options.sample_rate = config.sample_fps;
  options.skeleton_units = config.skeleton_units;
  options.warnings = &r->warnings;
  return ReadMotionFile(path, options, skeleton, motion);
}

// A glTF/GLB: the rigged character (skin, joints, meshes, bind pose), with or without
// animations, and the chosen animation's motion when it has any.
Status CharacterInfo(const std::string& path, const InfoConfig& config, InfoResult* r) {
  GltfDocument document;
  Status status = GltfDocument::Read(path, &document);
  if (!status.ok()) return status;
  const GltfContents contents = CountGltfContents(document);
  // The animation first (a bad --animation is an error before anything else).
  std::vector<std::string> clips;
  status = ReadAnimationNames(path, &clips);
  if (!status.ok()) return status;
  Skeleton animated_skeleton;
  Motion motion;
  if (!clips.empty()) {
    status = ReadInfoMotion(path, config, &animated_skeleton, &motion, r);
    if (!status.ok()) return status;
  } else if (!config.animation.empty()) {
    return Status::Error(path + ": --animation=" + config.animation + ": the file has no animation");
  }
  GltfCharacter character;
  if (contents.skins > 0) {
    status = ReadGltfCharacter(document, {}, &character);
    if (!status.ok()) return status;
    r->warnings.insert(r->warnings.end(), character.warnings.begin(), character.warnings.end());
  }
  r->meshes = contents.meshes;
  r->skinned_meshes = contents.skinned_meshes;
  r->primitives = contents.primitives;
  r->vertices = contents.vertices;
  r->nodes = contents.nodes;
  r->skins = contents.skins;
  r->report.Add("file", path);
  r->report.Add("meshes", contents.meshes).Add("skinned_meshes", contents.skinned_meshes)
      .Add("vertices", static_cast<double>(contents.vertices)).Add("skins", contents.skins);
  if (contents.skins == 0) {
    DescribeAnimations(clips, r);
    return Status::Ok();
  }
  r->skin_name = contents.skin_names[0];
  r->skinned_vertices = character.mesh.num_vertices();
  r->report.Add("skinned_vertices", r->skinned_vertices);
  DescribeSkeleton(character.skeleton, character.bind_pose, character.mesh.rest_positions(), r);
  DescribeAnimations(clips, r);
  if (!clips.empty()) DescribeMotion(motion, r);
  return Status::Ok();
}

// An FBX: its meshes and skins, the skeleton (the animated nodes, or without animation
// the skins' bones) at the nodes' default transforms, and the animation if any.
Status FbxFileInfo(const std::string& path, const InfoConfig& config, InfoResult* r) {
  FbxReadOptions options;
  options.animation = config.animation;
  options.frame_rate = config.sample_fps;
  options.skeleton_without_animation = true;
  Skeleton skeleton;
  Motion motion;
  FbxInfo info;
  Status status = ReadFbx(path, options, &skeleton, &motion, &info);
  if (!status.ok()) return status;
  r->warnings = info.warnings;
  r->meshes = info.meshes;
  r->skinned_meshes = info.skinned_meshes;
  r->vertices = info.vertices;
  r->bones = info.bones;
  r->report.Add("file", path);
  r->report.Add("meshes", info.meshes).Add("skinned_meshes", info.skinned_meshes)
      .Add("vertices", static_cast<double>(info.vertices)).Add("bones", info.bones);
  const bool mesh = info.skinned_meshes > 0 && info.mesh_vertices.cols() > 0;
  DescribeSkeleton(skeleton, info.default_pose, mesh ? info.mesh_vertices : Eigen::Matrix3Xd(3, 0), r);
  DescribeAnimations(info.animation_names, r);
  if (!info.animation_names.empty()) DescribeMotion(motion, r);
  return Status::Ok();
}

}  // namespace

Status RunInfo(const std::string& path, const InfoConfig& config, InfoResult* result) {
  *result = InfoResult();
  InfoResult& r = *result;
  r.path = path;
  const std::string ext = FileExtension(path);
  if (IsMarkerFile(path)) {
    r.kind = InfoKind::kMarkers;
    return MarkerInfo(path, &r);
  }
  if (ext == ".glb" || ext == ".gltf") {
    r.kind = InfoKind::kCharacter;
    return CharacterInfo(path, config, &r);
  }
  if (ext == ".fbx") {
    r.kind = InfoKind::kFbx;
    return FbxFileInfo(path, config, &r);
  }
  Skeleton skeleton;
  if (ext == ".asf") {
    // A skeleton file without motion: the skeleton in its rest pose.
    r.kind = InfoKind::kSkeleton;
    Status status = ReadSkeletonFile(path, &skeleton);
    if (status.ok()) status = SetSkeletonUnits(config.skeleton_units, &skeleton);
    if (!status.ok()) return status;
    r.report.Add("file", path);
    DescribeSkeleton(skeleton, RestPose(skeleton), Eigen::Matrix3Xd(3, 0), &r);
    return Status::Ok();
  }
  r.kind = InfoKind::kMotion;
  Motion motion;
  Status status = ReadInfoMotion(path, config, &skeleton, &motion, &r);
  if (!status.ok()) return status;
  std::vector<std::string> clips;
  status = ReadAnimationNames(path, &clips);
  if (!status.ok()) return status;
  r.report.Add("file", path);
  DescribeSkeleton(skeleton, RestPose(skeleton), Eigen::Matrix3Xd(3, 0), &r);
  if (!clips.empty()) DescribeAnimations(clips, &r);
  DescribeMotion(motion, &r);
  return Status::Ok();
}

}  // namespace mocapsolve
