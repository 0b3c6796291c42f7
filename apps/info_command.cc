// mocapsolve info FILE: what a motion, skeleton, character or marker file holds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "io/fbx_reader.h"
#include "io/gltf_contents.h"
#include "io/gltf_reader.h"
#include "io/json_writer.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "kinematics/bind_pose_shape.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

// Marker files: labels, frames, rate, unit and gaps.
Status MarkerInfo(const std::string& path) {
  MarkerTrajectories markers;
  Status status = ReadMarkerFile(path, &markers);
  if (!status.ok()) return status;
  int gap_runs = 0;
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (int f = 0; f < markers.num_frames(); ++f) {
      if (!markers.valid(f, m) && (f == 0 || markers.valid(f - 1, m))) ++gap_runs;
    }
  }
  const double duration = markers.frame_rate > 0 && markers.num_frames() > 0
                              ? (markers.num_frames() - 1) / markers.frame_rate : 0.0;
  // Names from the file (and the path) go through TerminalText: a label holding ESC
  // must not drive the terminal.
  std::printf("file:      %s\n", TerminalText(path).c_str());
  std::printf("markers:   %d", markers.num_markers());
  for (int m = 0; m < std::min(markers.num_markers(), 8); ++m) {
    std::printf("%s%s", m ? ", " : " (", TerminalText(markers.label(m)).c_str());
  }
  std::printf("%s\n", markers.num_markers() > 8 ? ", ...)" : markers.num_markers() ? ")" : "");
  if (markers.model_outputs != nullptr) {
    const MarkerTrajectories& outputs = markers.model_outputs->points;
    std::printf("outputs:   %d model outputs, not markers", outputs.num_markers());
    for (int m = 0; m < std::min(outputs.num_markers(), 4); ++m) {
      std::printf("%s%s", m ? ", " : " (", TerminalText(outputs.label(m)).c_str());
    }
    std::printf("%s\n", outputs.num_markers() > 4 ? ", ...)" : ")");
  }
  std::printf("frames:    %d at %.6g fps (%.4g s), first frame %d\n", markers.num_frames(),
              markers.frame_rate, duration, markers.first_frame);
  std::printf("units:     %s\n", TerminalText(markers.unit.name).c_str());
  std::printf("missing:   %d of %d samples, %d gap runs\n", markers.CountMissing(),
              markers.num_frames() * markers.num_markers(), gap_runs);
  JsonObject report;
  report.Add("file", path).Add("markers", markers.num_markers()).Add("frames", markers.num_frames())
      .Add("frame_rate", markers.frame_rate).Add("units", markers.unit.name)
      .Add("missing_samples", markers.CountMissing()).Add("gap_runs", gap_runs);
  return WriteReport(report);
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

std::string LengthText(double length, const LengthUnit& unit) {
  char text[96];
  if (unit.known() && unit.metres_per_unit == 1.0) {
    std::snprintf(text, sizeof(text), "%.3f m", length);
  } else if (unit.known()) {
    std::snprintf(text, sizeof(text), "%.3f m (%.4g %s)", length * unit.metres_per_unit, length, TerminalText(unit.name).c_str());
  } else {
    std::snprintf(text, sizeof(text), "%.4g file units (the file states no unit)", length);
  }
  return text;
}

// The skeleton and its bind pose: joints by level, height, T-/A-pose. `vertices`: the
// bind-pose mesh (may be empty).
void DescribeSkeleton(const Skeleton& skeleton, const Pose& bind_pose, const Eigen::Matrix3Xd& vertices,
                      JsonObject* report) {
  std::printf("joints:    %d (+%zu end sites), root '%s'\n", skeleton.num_joints(), skeleton.end_sites().size(),
              TerminalText(skeleton.name(0)).c_str());
  const std::vector<std::vector<std::string>> levels = JointLevels(skeleton, 2);
  std::string levels_json = "[";
  for (size_t d = 1; d < levels.size(); ++d) {
    std::printf("  level %zu: %zu joint%s:", d, levels[d].size(), levels[d].size() == 1 ? "" : "s");
    for (size_t k = 0; k < levels[d].size() && k < 12; ++k) std::printf("%s %s", k ? "," : "", TerminalText(levels[d][k]).c_str());
    std::printf("%s\n", levels[d].size() > 12 ? ", ..." : "");
  }
  for (size_t d = 0; d < levels.size(); ++d) {
    levels_json += d ? ", [" : "[";
    for (size_t k = 0; k < levels[d].size(); ++k) levels_json += (k ? ", " : "") + JsonQuote(levels[d][k]);
    levels_json += "]";
  }
  levels_json += "]";
  const BindPoseShape shape = DescribeBindPose(skeleton, bind_pose, vertices);
  const char* axis = shape.up_axis == 0 ? "X" : shape.up_axis == 1 ? "Y" : "Z";
  std::printf("height:    %s (%s, along %s%s)\n", LengthText(shape.height, skeleton.unit()).c_str(),
              shape.height_from_mesh ? "bind-pose mesh" : "bind-pose joints", shape.up_sign > 0 ? "+" : "-", axis);
  if (shape.upper_arms[0].empty()) {
    std::printf("bind pose: other (%s)\n", shape.reason.c_str());
  } else {
    const auto shown = [](double degrees) { return std::round(degrees * 10.0) / 10.0 + 0.0; };  // No "-0.0".
    std::printf("bind pose: %s (upper arms %.1f and %.1f deg below horizontal: %s, %s)\n", shape.kind.c_str(),
                shown(shape.below_horizontal_deg[0]), shown(shape.below_horizontal_deg[1]), shape.upper_arms[0].c_str(),
                shape.upper_arms[1].c_str());
  }
  report->Add("joints", skeleton.num_joints())
      .Add("end_sites", static_cast<int>(skeleton.end_sites().size()))
      .Add("root", skeleton.name(0))
      .Add("joint_levels", JsonValue::Raw(levels_json))
      .Add("units", skeleton.unit().name)
      .Add("metres_per_unit", skeleton.unit().metres_per_unit)
      .Add("height", shape.height)
      .Add("height_m", skeleton.unit().known() ? JsonValue(shape.height * skeleton.unit().metres_per_unit) : JsonValue())
      .Add("height_from", shape.height_from_mesh ? "mesh" : "joints")
      .Add("up_axis", std::string(shape.up_sign > 0 ? "+" : "-") + axis)
      .Add("bind_pose", shape.kind);
  if (!shape.upper_arms[0].empty()) {
    report->Add("upper_arms", std::vector<JsonValue>{shape.upper_arms[0], shape.upper_arms[1]})
        .Add("upper_arms_below_horizontal_deg",
             std::vector<JsonValue>{shape.below_horizontal_deg[0], shape.below_horizontal_deg[1]});
  }
}

void DescribeUnit(const LengthUnit& unit) {
  if (unit.known()) {
    std::printf("units:     %s (%.6g m per unit)\n", TerminalText(unit.name).c_str(), unit.metres_per_unit);
  } else {
    std::printf("units:     not stated by the file (lengths are in file units)\n");
  }
}

void DescribeAnimations(const std::vector<std::string>& clips, JsonObject* report) {
  if (clips.empty()) {
    std::printf("animations: none\n");
  } else {
    std::printf("animations: %zu:", clips.size());
    for (size_t k = 0; k < clips.size(); ++k) std::printf("%s %zu '%s'", k ? "," : "", k, TerminalText(clips[k]).c_str());
    std::printf(" (pick one with --animation=NAME or index)\n");
  }
  report->Add("animations", std::vector<JsonValue>(clips.begin(), clips.end()));
}

// Frames, rate, duration and the root's path of one motion.
void DescribeMotion(const Motion& motion, JsonObject* report) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Pose& pose : motion.frames) {
    lo = lo.cwiseMin(pose.translations[0]);
    hi = hi.cwiseMax(pose.translations[0]);
  }
  if (motion.frames.empty()) lo = hi = Eigen::Vector3d::Zero();
  std::printf("frames:    %d at %.6g fps (%.4g s)\n", motion.num_frames(), motion.frame_rate,
              motion.duration_seconds());
  std::printf("root path: min (%.4g, %.4g, %.4g) max (%.4g, %.4g, %.4g) extent (%.4g, %.4g, %.4g)\n",
              lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z(), hi.x() - lo.x(), hi.y() - lo.y(),
              hi.z() - lo.z());
  report->Add("frames", motion.num_frames())
      .Add("frame_rate", motion.frame_rate)
      .Add("duration_s", motion.duration_seconds())
      .Add("root_min", std::vector<JsonValue>{lo.x(), lo.y(), lo.z()})
      .Add("root_max", std::vector<JsonValue>{hi.x(), hi.y(), hi.z()});
}

// A glTF/GLB: the rigged character (skin, joints, meshes, bind pose), with or without
// animations, and the chosen animation's motion when it has any.
Status CharacterInfo(const std::string& path) {
  GltfDocument document;
  Status status = GltfDocument::Read(path, &document);
  if (!status.ok()) return status;
  const GltfContents contents = CountGltfContents(document);
  // The animation first (a bad --animation is an error before anything is printed).
  std::vector<std::string> clips;
  status = ReadAnimationNames(path, &clips);
  if (!status.ok()) return status;
  Skeleton animated_skeleton;
  Motion motion;
  if (!clips.empty()) {
    status = LoadMotion(path, &animated_skeleton, &motion);
    if (!status.ok()) return status;
  } else if (!FLAGS_animation.empty()) {
    return Status::Error(path + ": --animation=" + FLAGS_animation + ": the file has no animation");
  }
  GltfCharacter character;
  if (contents.skins > 0) {
    status = ReadGltfCharacter(document, {}, &character);
    if (!status.ok()) return status;
    for (const std::string& warning : character.warnings) std::fprintf(stderr, "warning: %s\n", TerminalText(warning).c_str());
  }
  JsonObject report;
  report.Add("file", path);
  std::printf("file:      %s\n", TerminalText(path).c_str());
  std::printf("meshes:    %d (%d skinned), %d primitives, %lld vertices; %d node%s\n", contents.meshes,
              contents.skinned_meshes, contents.primitives, contents.vertices, contents.nodes,
              contents.nodes == 1 ? "" : "s");
  report.Add("meshes", contents.meshes).Add("skinned_meshes", contents.skinned_meshes)
      .Add("vertices", static_cast<double>(contents.vertices)).Add("skins", contents.skins);
  if (contents.skins == 0) {
    std::printf("skins:     none (not a rigged character)\n");
    DescribeAnimations(clips, &report);
    return WriteReport(report);
  }
  std::printf("skins:     %d; skin 0%s%s%s: %d vertices skinned\n", contents.skins,
              contents.skin_names[0].empty() ? "" : " '", TerminalText(contents.skin_names[0]).c_str(),
              contents.skin_names[0].empty() ? "" : "'", character.mesh.num_vertices());
  report.Add("skinned_vertices", character.mesh.num_vertices());
  DescribeUnit(character.skeleton.unit());
  DescribeSkeleton(character.skeleton, character.bind_pose, character.mesh.rest_positions(), &report);
  DescribeAnimations(clips, &report);
  if (!clips.empty()) DescribeMotion(motion, &report);
  return WriteReport(report);
}

// An FBX: its meshes and skins, the skeleton (the animated nodes, or without animation
// the skins' bones) at the nodes' default transforms, and the animation if any.
Status FbxFileInfo(const std::string& path) {
  FbxReadOptions options;
  options.animation = FLAGS_animation;
  options.frame_rate = FLAGS_sample_fps;
  options.skeleton_without_animation = true;
  Skeleton skeleton;
  Motion motion;
  FbxInfo info;
  Status status = ReadFbx(path, options, &skeleton, &motion, &info);
  if (!status.ok()) return status;
  for (const std::string& warning : info.warnings) std::fprintf(stderr, "warning: %s\n", TerminalText(warning).c_str());
  JsonObject report;
  report.Add("file", path);
  std::printf("file:      %s\n", TerminalText(path).c_str());
  std::printf("meshes:    %d (%d skinned), %lld vertices; %d bones\n", info.meshes, info.skinned_meshes, info.vertices,
              info.bones);
  report.Add("meshes", info.meshes).Add("skinned_meshes", info.skinned_meshes)
      .Add("vertices", static_cast<double>(info.vertices)).Add("bones", info.bones);
  DescribeUnit(skeleton.unit());
  const bool mesh = info.skinned_meshes > 0 && info.mesh_vertices.cols() > 0;
  DescribeSkeleton(skeleton, info.default_pose, mesh ? info.mesh_vertices : Eigen::Matrix3Xd(3, 0), &report);
  DescribeAnimations(info.animation_names, &report);
  if (!info.animation_names.empty()) DescribeMotion(motion, &report);
  return WriteReport(report);
}

// The file, its unit and its skeleton in the rest pose: what a skeleton or motion file
// says first.
void DescribeSkeletonFile(const std::string& path, const Skeleton& skeleton, JsonObject* report) {
  report->Add("file", path);
  std::printf("file:      %s\n", TerminalText(path).c_str());
  DescribeUnit(skeleton.unit());
  DescribeSkeleton(skeleton, RestPose(skeleton), Eigen::Matrix3Xd(3, 0), report);
}

// A skeleton file without motion (.asf): the skeleton in its rest pose.
Status SkeletonInfo(const std::string& path) {
  Skeleton skeleton;
  Status status = LoadSkeleton(path, &skeleton);
  if (!status.ok()) return status;
  JsonObject report;
  DescribeSkeletonFile(path, skeleton, &report);
  std::printf("frames:    none (a skeleton file)\n");
  return WriteReport(report);
}

Status RunInfo(const std::vector<std::string>& arguments) {
  if (arguments.size() != 1) return Status::Error("expected one file (mocapsolve info FILE)");
  const std::string& path = arguments[0];
  if (IsMarkerFile(path)) return MarkerInfo(path);
  const std::string ext = FileExtension(path);
  if (ext == ".glb" || ext == ".gltf") return CharacterInfo(path);
  if (ext == ".asf") return SkeletonInfo(path);
  if (ext == ".fbx") return FbxFileInfo(path);
  Skeleton skeleton;
  Motion motion;
  Status status = LoadMotion(path, &skeleton, &motion);
  if (!status.ok()) return status;
  std::vector<std::string> clips;
  status = ReadAnimationNames(path, &clips);
  if (!status.ok()) return status;
  JsonObject report;
  DescribeSkeletonFile(path, skeleton, &report);
  if (!clips.empty()) DescribeAnimations(clips, &report);
  DescribeMotion(motion, &report);
  return WriteReport(report);
}

}  // namespace

extern const Command kInfoCommand = {
    "info", "what a character (glTF/GLB), motion (BVH, ASF/AMC, FBX), skeleton (ASF) or marker (C3D, TRC) file holds",
    "mocapsolve info FILE.glb|.gltf [--animation=NAME] | FILE.bvh | FILE.amc --skeleton=FILE.asf | FILE.asf | "
    "FILE.fbx [--animation=NAME] | FILE.c3d | FILE.trc [--report=info.json]\n\n"
    "Skeletons (every file but markers): joint and end-site counts, the root and the first\n"
    "levels below it, the height (bind-pose mesh of a character, else the joints of the\n"
    "rest pose; with the unit) and the bind pose's kind: T-pose, A-pose or other, from the\n"
    "upper arms' angle below horizontal about the body's up axis (kinematics/bind_pose_shape.h).\n"
    "Characters (glTF/GLB, with or without animation): also meshes, primitives, vertices,\n"
    "skins and the animations. Motions: frame count and rate, duration, the file's length\n"
    "unit (BVH does not state one) and the bounding box of the root's path. Markers: labels,\n"
    "frames, rate, unit, missing samples and gap runs.",
    __FILE__, RunInfo, "skeleton,skeleton_units,amc_fps,animation,sample_fps,report"};

}  // namespace mocapsolve
