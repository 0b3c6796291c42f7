// mocapsolve info FILE: what a motion, skeleton, character or marker file holds
// (tasks/info_task.h reads and counts; this prints it and writes the report).
#include <cmath>
#include <cstdio>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "kinematics/quote_token.h"
#include "tasks/info_task.h"

namespace mocapsolve {
namespace {

// Names from the file (and the path) go through TerminalText: a label holding ESC must
// not drive the terminal. PrintNames: " (a, b, ...)", the first `most` names.
void PrintNames(const std::vector<std::string>& names, size_t most, bool parentheses_when_empty) {
  for (size_t k = 0; k < names.size() && k < most; ++k) {
    std::printf("%s%s", k ? ", " : " (", TerminalText(names[k]).c_str());
  }
  std::printf("%s\n", names.size() > most ? ", ...)" : !names.empty() || parentheses_when_empty ? ")" : "");
}

void PrintMarkers(const InfoMarkers& m) {
  std::printf("markers:   %zu", m.labels.size());
  PrintNames(m.labels, 8, false);
  if (m.has_model_outputs) {
    std::printf("outputs:   %zu model outputs, not markers", m.model_outputs.size());
    PrintNames(m.model_outputs, 4, true);
  }
  std::printf("frames:    %d at %.6g fps (%.4g s), first frame %d\n", m.frames, m.frame_rate, m.duration_s,
              m.first_frame);
  std::printf("units:     %s\n", TerminalText(m.units).c_str());
  std::printf("missing:   %d of %d samples, %d gap runs\n", m.missing, m.samples, m.gap_runs);
}

std::string LengthText(double length, const LengthUnit& unit) {
  char text[96];
  if (unit.known() && unit.metres_per_unit == 1.0) {
    std::snprintf(text, sizeof(text), "%.3f m", length);
  } else if (unit.known()) {
    std::snprintf(text, sizeof(text), "%.3f m (%.4g %s)", length * unit.metres_per_unit, length,
                  TerminalText(unit.name).c_str());
  } else {
    std::snprintf(text, sizeof(text), "%.4g file units (the file states no unit)", length);
  }
  return text;
}

void PrintUnit(const LengthUnit& unit) {
  if (unit.known()) std::printf("units:     %s (%.6g m per unit)\n", TerminalText(unit.name).c_str(), unit.metres_per_unit);
  else std::printf("units:     not stated by the file (lengths are in file units)\n");
}

// Joints by level, height, T-/A-pose.
void PrintSkeleton(const InfoSkeleton& s) {
  std::printf("joints:    %d (+%d end sites), root '%s'\n", s.joints, s.end_sites, TerminalText(s.root).c_str());
  for (size_t d = 1; d < s.levels.size(); ++d) {
    const std::vector<std::string>& level = s.levels[d];
    std::printf("  level %zu: %zu joint%s:", d, level.size(), level.size() == 1 ? "" : "s");
    for (size_t k = 0; k < level.size() && k < 12; ++k) std::printf("%s %s", k ? "," : "", TerminalText(level[k]).c_str());
    std::printf("%s\n", level.size() > 12 ? ", ..." : "");
  }
  const BindPoseShape& shape = s.shape;
  const char* axis = shape.up_axis == 0 ? "X" : shape.up_axis == 1 ? "Y" : "Z";
  std::printf("height:    %s (%s, along %s%s)\n", LengthText(shape.height, s.unit).c_str(),
              shape.height_from_mesh ? "bind-pose mesh" : "bind-pose joints", shape.up_sign > 0 ? "+" : "-", axis);
  if (shape.upper_arms[0].empty()) {
    std::printf("bind pose: other (%s)\n", shape.reason.c_str());
  } else {
    const auto shown = [](double degrees) { return std::round(degrees * 10.0) / 10.0 + 0.0; };  // No "-0.0".
    std::printf("bind pose: %s (upper arms %.1f and %.1f deg below horizontal: %s, %s)\n", shape.kind.c_str(),
                shown(shape.below_horizontal_deg[0]), shown(shape.below_horizontal_deg[1]), shape.upper_arms[0].c_str(),
                shape.upper_arms[1].c_str());
  }
}

void PrintAnimations(const std::vector<std::string>& clips) {
  if (clips.empty()) {
    std::printf("animations: none\n");
    return;
  }
  std::printf("animations: %zu:", clips.size());
  for (size_t k = 0; k < clips.size(); ++k) std::printf("%s %zu '%s'", k ? "," : "", k, TerminalText(clips[k]).c_str());
  std::printf(" (pick one with --animation=NAME or index)\n");
}

void PrintMotion(const InfoMotion& m) {
  const Eigen::Vector3d &lo = m.root_min, &hi = m.root_max;
  std::printf("frames:    %d at %.6g fps (%.4g s)\n", m.frames, m.frame_rate, m.duration_s);
  std::printf("root path: min (%.4g, %.4g, %.4g) max (%.4g, %.4g, %.4g) extent (%.4g, %.4g, %.4g)\n",
              lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z(), hi.x() - lo.x(), hi.y() - lo.y(), hi.z() - lo.z());
}

void Print(const InfoResult& r) {
  std::printf("file:      %s\n", TerminalText(r.path).c_str());
  if (r.kind == InfoKind::kMarkers) return PrintMarkers(r.markers);
  if (r.kind == InfoKind::kCharacter) {
    std::printf("meshes:    %d (%d skinned), %d primitives, %lld vertices; %d node%s\n", r.meshes, r.skinned_meshes,
                r.primitives, r.vertices, r.nodes, r.nodes == 1 ? "" : "s");
    if (r.skins == 0) {
      std::printf("skins:     none (not a rigged character)\n");
      return PrintAnimations(r.animations);
    }
    std::printf("skins:     %d; skin 0%s%s%s: %d vertices skinned\n", r.skins, r.skin_name.empty() ? "" : " '",
                TerminalText(r.skin_name).c_str(), r.skin_name.empty() ? "" : "'", r.skinned_vertices);
  } else if (r.kind == InfoKind::kFbx) {
    std::printf("meshes:    %d (%d skinned), %lld vertices; %d bones\n", r.meshes, r.skinned_meshes, r.vertices,
                r.bones);
  }
  PrintUnit(r.skeleton.unit);
  PrintSkeleton(r.skeleton);
  if (r.kind == InfoKind::kSkeleton) {
    std::printf("frames:    none (a skeleton file)\n");
  } else if (r.kind != InfoKind::kMotion || !r.animations.empty()) {
    PrintAnimations(r.animations);  // A BVH or AMC lists none.
  }
  if (r.has_motion) PrintMotion(r.motion);
}

Status InfoMain(const std::vector<std::string>& arguments) {
  if (arguments.size() != 1) return Status::Error("expected one file (mocapsolve info FILE)");
  // InfoConfig's fields in order.
  const InfoConfig config{Files().skeleton, FileReading().skeleton_units, FileReading().amc_fps, FileReading().animation, FileReading().sample_fps};
  InfoResult result;
  const Status status = RunInfo(arguments[0], config, &result);
  for (const std::string& warning : result.warnings) {
    std::fprintf(stderr, "warning: %s\n", TerminalText(warning).c_str());
  }
  if (!status.ok()) return status;
  Print(result);
  return WriteReport(result.report);
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
    __FILE__, InfoMain, {SharedOptions("skeleton,skeleton_units,amc_fps,animation,sample_fps,include_model_outputs,subject_prefix,ignore_markers,report")}};

}  // namespace mocapsolve
