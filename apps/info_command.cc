// mocapsolve info FILE: what a motion file holds.
#include <algorithm>
#include <cstdio>
#include <limits>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
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

Status RunInfo(const std::vector<std::string>& arguments) {
  if (arguments.size() != 1) return Status::Error("expected one file (mocapsolve info FILE)");
  const std::string& path = arguments[0];
  if (IsMarkerFile(path)) return MarkerInfo(path);
  Skeleton skeleton;
  Motion motion;
  Status status = LoadMotion(path, &skeleton, &motion);
  if (!status.ok()) return status;

  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Pose& pose : motion.frames) {
    lo = lo.cwiseMin(pose.translations[0]);
    hi = hi.cwiseMax(pose.translations[0]);
  }
  if (motion.frames.empty()) lo = hi = Eigen::Vector3d::Zero();
  const LengthUnit& unit = skeleton.unit();
  std::printf("file:      %s\n", TerminalText(path).c_str());
  std::printf("joints:    %d (+%zu end sites), root '%s'\n", skeleton.num_joints(),
              skeleton.end_sites().size(), TerminalText(skeleton.name(0)).c_str());
  std::printf("frames:    %d at %.6g fps (%.4g s)\n", motion.num_frames(), motion.frame_rate,
              motion.duration_seconds());
  if (unit.known()) {
    std::printf("units:     %s (%.6g m per unit)\n", TerminalText(unit.name).c_str(), unit.metres_per_unit);
  } else {
    std::printf("units:     not stated by the file (lengths below are in file units)\n");
  }
  std::vector<std::string> clips;
  status = ReadAnimationNames(path, &clips);
  if (!status.ok()) return status;
  if (!clips.empty()) {
    std::printf("clips:     %zu:", clips.size());
    for (size_t k = 0; k < clips.size(); ++k) std::printf("%s %zu '%s'", k ? "," : "", k, TerminalText(clips[k]).c_str());
    std::printf(" (pick one with --animation=NAME or index)\n");
  }
  std::printf("root path: min (%.4g, %.4g, %.4g) max (%.4g, %.4g, %.4g) extent (%.4g, %.4g, %.4g)\n",
              lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z(), hi.x() - lo.x(), hi.y() - lo.y(),
              hi.z() - lo.z());
  JsonObject report;
  report.Add("file", path)
      .Add("joints", skeleton.num_joints())
      .Add("end_sites", static_cast<int>(skeleton.end_sites().size()))
      .Add("frames", motion.num_frames())
      .Add("frame_rate", motion.frame_rate)
      .Add("duration_s", motion.duration_seconds())
      .Add("units", unit.name)
      .Add("metres_per_unit", unit.metres_per_unit)
      .Add("root_min", std::vector<JsonValue>{lo.x(), lo.y(), lo.z()})
      .Add("root_max", std::vector<JsonValue>{hi.x(), hi.y(), hi.z()});
  if (!clips.empty()) {
    std::vector<JsonValue> names(clips.begin(), clips.end());
    report.Add("animations", names);
  }
  return WriteReport(report);
}

}  // namespace

extern const Command kInfoCommand = {
    "info", "what a motion (BVH, ASF/AMC, glTF/GLB, FBX) or marker (C3D, TRC) file holds",
    "mocapsolve info FILE.bvh | FILE.amc --skeleton=FILE.asf | FILE.glb|.gltf|.fbx "
    "[--animation=NAME] | FILE.c3d | FILE.trc [--report=info.json]\n\n"
    "Motions: joint and end-site counts, frame count and rate, duration, the file's length\n"
    "unit (BVH does not state one) and the bounding box of the root's path. Markers:\n"
    "labels, frames, rate, unit, missing samples and gap runs.",
    __FILE__, RunInfo, "skeleton,skeleton_units,amc_fps,animation,sample_fps,report"};

}  // namespace mocapsolve
