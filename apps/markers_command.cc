// mocapsolve markers --motion=M --markerset=J|auto:N --out=OUT.c3d|.trc: synthetic marker
// trajectories from a motion and a marker set (thesis eq. 9, x_m = MarkerSet::Position
// after FK), optionally with Gaussian noise.
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "apps/progress.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "tasks/markers_task.h"


namespace mocapsolve {
namespace {

Status MarkersMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (Files().motion.empty() || Files().markerset.empty() || Files().out.empty()) {
    return Status::Error("--motion, --markerset (FILE.json or auto:N) and --out are required");
  }
  if (!IsMarkerFile(Files().out)) return Status::Error(Files().out + ": expected a .c3d or .trc output");
  const bool auto_set = Files().markerset.compare(0, 5, "auto:") == 0;
  if (!Files().write_markerset.empty() && !IsTextOutputPath(Files().write_markerset, ".json")) {
    return Status::Error(Files().write_markerset + ": expected a .json marker set file");
  }
  for (const std::string& output : {Files().out, Files().write_markerset}) {
    if (output.empty()) continue;
    for (const std::string& input : {Files().motion, Files().skeleton, auto_set ? std::string() : Files().markerset}) {
      if (input.empty()) continue;
      Status status = CheckNotAnInput(output, input);
      if (!status.ok()) return status;
    }
  }
  if (Files().out == Files().write_markerset) return Status::Error("--out and --write_markerset name the same file");

  Skeleton skeleton;
  Motion motion;
  Status status = LoadMotion(Files().motion, &skeleton, &motion);
  if (status.ok()) status = RequireFrames(Files().motion, motion);
  if (!status.ok()) return status;
  MarkersConfig config;
  config.markerset = Files().markerset;
  config.axes = FileReading().axes;
  config.marker_scale = FileReading().marker_scale;
  ReadOptionFlags(SyntheticMarkerOptions(), &config.markers);
  MarkersResult result;
  Progress progress("markers", motion.num_frames(), Console().quiet);
  status = RunMarkers(skeleton, motion, Files().motion, config, [&](int done) { progress.Update(done); }, &result);
  if (!status.ok()) return status;
  if (!result.warning.empty() && !Console().quiet) std::fprintf(stderr, "warning: %s\n", result.warning.c_str());
  const MarkerTrajectories& trajectories = result.trajectories;
  if (FileExtension(Files().out) == ".trc" && !trajectories.unit.known()) {
    return Status::Error(Files().out + ": TRC needs a known unit; give --skeleton_units (the motion's unit)");
  }
  const MarkerSet& marker_set = result.marker_set;
  if (!Files().write_markerset.empty()) {
    status = WriteMarkerSet(Files().write_markerset, skeleton, marker_set, Files().motion);
    if (!status.ok()) return status;
  }
  status = WriteMarkerFile(Files().out, trajectories);
  if (!status.ok()) return status;
  std::printf("wrote %s: %d markers x %d frames at %g fps (%s, axes %s, noise %g mm)\n",
              Files().out.c_str(), marker_set.num_markers(), motion.num_frames(), motion.frame_rate,
              trajectories.unit.name.c_str(), FileReading().axes.c_str(), config.markers.noise_mm);
  if (!Files().write_markerset.empty()) std::printf("wrote %s\n", Files().write_markerset.c_str());
  JsonObject report;
  report.Add("motion", Files().motion).Add("markerset", Files().markerset).Add("out", Files().out).Merge(result.report);
  return WriteReport(report);
}

}  // namespace

extern const Command kMarkersCommand = {
    "markers", "synthesize marker trajectories (C3D/TRC) from a motion and a marker set",
    "mocapsolve markers --motion=FILE.bvh|FILE.amc [--skeleton=X.asf] --markerset=SET.json|auto:N[:SEED]\n"
    "          --out=OUT.c3d|OUT.trc [--noise_mm=0 --seed=1] [--units=mm] [--skeleton_units=cm]\n"
    "          [--axes=x,y,z] [--marker_scale=0] [--write_markerset=SET.json]\n\n"
    "Runs FK on every frame and writes each marker's position x_m = sum_k w_k G_j(k) z_k\n"
    "(eq. 9). --markerset=auto:N puts N markers around every bone (deterministic for a\n"
    "seed; --write_markerset saves that set). Positions are converted from the skeleton's\n"
    "unit into --units (default mm) when the skeleton states its unit (ASF does, BVH does\n"
    "not: give --skeleton_units, otherwise positions stay in skeleton units, unlabelled).\n"
    "--axes and --marker_scale mean what they mean for `calibrate` and `solve` (the file\n"
    "from the model): x_file = A^T x_model / scale. --noise_mm adds Gaussian noise of that\n"
    "standard deviation (mm) to each coordinate. Frame rate: the motion's.",
    __FILE__, MarkersMain,
    {SharedOptions("motion,markerset,out,write_markerset,skeleton,skeleton_units,amc_fps,animation,sample_fps,axes,marker_scale,report"),
     SyntheticMarkerOptions().options()}};

}  // namespace mocapsolve
