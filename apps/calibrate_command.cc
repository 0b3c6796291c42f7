// mocapsolve calibrate --motion=M --markers=C3D|TRC --out=set.json: where each marker sits
// on the skeleton (joint and offset), from a solved motion and the markers of the same take.
#include <cmath>
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "pipeline/subject.h"
#include "tasks/calibrate_task.h"


namespace mocapsolve {
namespace {

Status CalibrateMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (Files().motion.empty() || Files().markers.empty()) return Status::Error("--motion and --markers are required");
  // The subject file holds the marker set too, so either output is enough.
  if (Files().out.empty() && Files().out_subject.empty()) {
    return Status::Error("--out=SET.json and/or --out_subject=S.json is required");
  }
  if (!Files().out.empty() && !IsTextOutputPath(Files().out, ".json")) {
    return Status::Error(Files().out + ": expected a .json output");
  }
  CalibrateSettings settings;
  ReadOptionFlags(CalibrateSettingOptions(), &settings);
  Status status = CheckCalibrateSettings(settings);
  if (!status.ok()) return status;
  if (!Files().out_subject.empty() && !IsTextOutputPath(Files().out_subject, ".json")) {
    return Status::Error(Files().out_subject + ": expected a .json subject file");
  }
  const std::string attach_file = settings.attach == "auto" ? "" : settings.attach;
  status = CheckOutputsApart({Files().out, Files().out_subject}, {Files().motion, Files().skeleton, Files().markers, attach_file});
  if (!status.ok()) return status;

  Skeleton skeleton;
  Motion motion;
  SetStage("inputs");
  status = LoadMotion(Files().motion, &skeleton, &motion);
  if (status.ok()) status = RequireFrames(Files().motion, motion);
  if (!status.ok()) return status;
  MarkerTrajectories trajectories;
  status = ReadMarkerFile(Files().markers, &trajectories);
  if (status.ok()) status = RequireMarkerData(Files().markers, trajectories);
  if (!status.ok()) return status;
  if (!Console().quiet && trajectories.frame_rate > 0.0 && motion.frame_rate > 0.0 &&
      std::abs(trajectories.frame_rate / motion.frame_rate - 1.0) > 1e-6) {
    std::fprintf(stderr, "warning: marker rate %g fps differs from the motion's %g fps (frames are "
                 "matched by index)\n", trajectories.frame_rate, motion.frame_rate);
  }
  SubjectCalibrationOptions options;
  options.axes = FileReading().axes;
  options.marker_scale = FileReading().marker_scale;
  options.skeleton_path = Files().skeleton.empty() ? Files().motion : Files().skeleton;
  options.amc_fps = FileReading().amc_fps;
  options.markers_name = Files().markers;
  CalibrateTaskResult result;
  SetStage("calibrate");
  status = RunCalibrate(skeleton, motion, trajectories, settings, options, &result);
  if (!status.ok()) return status;
  SetStage("writing");
  if (!Files().out.empty()) {
    status = WriteMarkerSet(Files().out, skeleton, result.calibration.result.marker_set, options.skeleton_path);
    if (!status.ok()) return status;
  }
  if (!Files().out_subject.empty()) {
    status = WriteSubject(Files().out_subject, result.calibration.subject);
    if (!status.ok()) return status;
    std::printf("wrote subject %s\n", Files().out_subject.c_str());
  }
  std::fputs(result.table.c_str(), stdout);
  std::printf(Files().out.empty() ? "\n" : "; wrote %s\n", Files().out.c_str());
  if (!result.refit_line.empty()) std::printf("%s\n", result.refit_line.c_str());
  JsonObject report;
  report.Add("motion", Files().motion).Add("markers", Files().markers).Add("out", Files().out)
      .Add("out_subject", Files().out_subject).Merge(result.report);
  return WriteReport(report);
}

}  // namespace

extern const Command kCalibrateCommand = {
    "calibrate", "fit each marker's joint and offset from a solved motion and its markers",
    "mocapsolve calibrate --motion=FILE.bvh|FILE.amc [--skeleton=X.asf] --markers=FILE.c3d|.trc\n"
    "          (--out=markerset.json | --out_subject=S.json | both) [--attach=auto|SET.json] [--axes=x,y,z|auto]\n"
    "          [--marker_scale=0] [--skeleton_units=cm] [--frame_offset=0] [--report=r.json]\n\n"
    "Marker frame k + frame_offset is matched to motion frame k. Marker samples are taken\n"
    "into the model's frame as x_model = marker_scale * A x_file, with A from --axes\n"
    "('y,z,x' means (x, y, z)_model = (y, z, x)_file; 'auto' tries all 24 axis rotations\n"
    "and keeps the one of least RMS) and marker_scale from the files' units (C3D\n"
    "POINT:UNITS, TRC Units, ASF :units; --skeleton_units for a BVH). With --attach=auto\n"
    "each marker rides on the joint in whose frame it moves least, at its mean local\n"
    "position; with --attach=SET.json the joints come from the file and only offsets are\n"
    "re-estimated. Prints each marker's RMS (the floor for a solve on this motion) and\n"
    "writes the marker set in skeleton units (--out), or a subject file holding it with the\n"
    "skeleton, axes and units (--out_subject), or both.\n"
    "CMU (C3D from mocap.cs.cmu.edu with its ASF/AMC, e.g. 02_01): --axes=y,z,x, no frame\n"
    "offset, scale from the units (mm -> 1/0.45 inch): calibrated RMS 11.7 mm on 02_01.",
    __FILE__, CalibrateMain,
    {SharedOptions("motion,markers,out,out_subject,skeleton,skeleton_units,amc_fps,animation,sample_fps,axes,marker_scale,report"),
     CalibrateSettingOptions().options()}};

}  // namespace mocapsolve
