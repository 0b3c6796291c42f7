// mocapsolve calibrate --motion=M --markers=C3D|TRC --out=set.json: where each marker sits
// on the skeleton (joint and offset), from a solved motion and the markers of the same take.
#include <cmath>
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "kinematics/quote_token.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "kinematics/marker_trajectories.h"
#include "pipeline/subject.h"
#include "tasks/calibrate_task.h"
#include "problems/marker_solve/calibration.h"
#include "problems/marker_solve/marker_observations.h"

DEFINE_string(attach, "auto", "auto: each marker rides on the joint in whose frame it moves least; "
              "or a marker set .json whose joints are kept (only offsets re-estimated).");
DEFINE_int32(frame_offset, 0, "Marker frame index = motion frame index + this (CMU 02_01 C3D vs AMC: 0).");
DEFINE_string(out_subject, "", "Also write a subject file (.json: skeleton, marker set, axes, units) "
              "that solve/repair/evaluate take as --subject.");
DEFINE_int32(min_valid_frames, 2, "Markers valid in fewer matched frames are left out.");

namespace mocapsolve {
namespace {


Status RunCalibrate(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (FLAGS_motion.empty() || FLAGS_markers.empty()) return Status::Error("--motion and --markers are required");
  // The subject file holds the marker set too, so either output is enough.
  if (FLAGS_out.empty() && FLAGS_out_subject.empty()) {
    return Status::Error("--out=SET.json and/or --out_subject=S.json is required");
  }
  if (!FLAGS_out.empty() && !IsTextOutputPath(FLAGS_out, ".json")) {
    return Status::Error(FLAGS_out + ": expected a .json output");
  }
  const bool auto_attach = FLAGS_attach == "auto";
  if (!auto_attach && FileExtension(FLAGS_attach) != ".json") {
    return Status::Error("--attach='" + FLAGS_attach + "': expected auto or a marker set .json");
  }
  if (!FLAGS_out_subject.empty() && !IsTextOutputPath(FLAGS_out_subject, ".json")) {
    return Status::Error(FLAGS_out_subject + ": expected a .json subject file");
  }
  Status status = CheckOutputsApart({FLAGS_out, FLAGS_out_subject},
                                    {FLAGS_motion, FLAGS_skeleton, FLAGS_markers, auto_attach ? "" : FLAGS_attach});
  if (!status.ok()) return status;

  Skeleton skeleton;
  Motion motion;
  SetStage("inputs");
  status = LoadMotion(FLAGS_motion, &skeleton, &motion);
  if (status.ok()) status = RequireFrames(FLAGS_motion, motion);
  if (!status.ok()) return status;
  MarkerTrajectories trajectories;
  status = ReadMarkerFile(FLAGS_markers, &trajectories);
  if (status.ok()) status = RequireMarkerData(FLAGS_markers, trajectories);
  if (!status.ok()) return status;
  MarkerSet attachments;
  if (!auto_attach) {
    status = ReadMarkerSet(FLAGS_attach, skeleton, &attachments);
    if (!status.ok()) return status;
  }

  if (!FLAGS_quiet && trajectories.frame_rate > 0.0 && motion.frame_rate > 0.0 &&
      std::abs(trajectories.frame_rate / motion.frame_rate - 1.0) > 1e-6) {
    std::fprintf(stderr, "warning: marker rate %g fps differs from the motion's %g fps (frames are "
                 "matched by index)\n", trajectories.frame_rate, motion.frame_rate);
  }
  SubjectCalibrationOptions options;
  options.axes = FLAGS_axes;
  options.marker_scale = FLAGS_marker_scale;
  options.frame_offset = FLAGS_frame_offset;
  options.min_valid_frames = FLAGS_min_valid_frames;
  options.attachments = auto_attach ? nullptr : &attachments;
  options.skeleton_path = FLAGS_skeleton.empty() ? FLAGS_motion : FLAGS_skeleton;
  options.amc_fps = FLAGS_amc_fps;
  options.markers_name = FLAGS_markers;
  SubjectCalibration calibration;
  SetStage("calibrate");
  status = CalibrateSubject(skeleton, motion, trajectories, options, &calibration);
  if (!status.ok()) return status;
  const CalibrationResult& result = calibration.result;
  const MarkerFileToModel& transform = calibration.transform;
  const std::vector<double>& axis_rms = calibration.axis_rms;
  SetStage("writing");
  if (!FLAGS_out.empty()) {
    status = WriteMarkerSet(FLAGS_out, skeleton, result.marker_set, options.skeleton_path);
    if (!status.ok()) return status;
  }
  if (!FLAGS_out_subject.empty()) {
    status = WriteSubject(FLAGS_out_subject, calibration.subject);
    if (!status.ok()) return status;
    std::printf("wrote subject %s\n", FLAGS_out_subject.c_str());
  }

  // mm per skeleton unit when known, for a figure people can read.
  const double mm = skeleton.unit().known() ? skeleton.unit().metres_per_unit * 1000.0 : 0.0;
  const auto length = [&](double value, bool pad) {
    char text[64];
    if (mm > 0.0) {
      std::snprintf(text, sizeof text, pad ? "%8.3f mm" : "%.3f mm", value * mm);
    } else {
      std::snprintf(text, sizeof text, pad ? "%8.4g units" : "%.4g units", value);
    }
    return std::string(text);
  };
  std::printf("axes %s, scale %.9g (marker units -> %s), frames %d..%d of the motion (offset %d)\n",
              AxesName(transform.rotation).c_str(), transform.scale, skeleton.unit().name.c_str(),
              result.first_motion_frame, result.first_motion_frame + result.matched_frames - 1,
              FLAGS_frame_offset);
  std::printf("%-12s %-14s %7s %12s %12s  %s\n", "marker", "joint", "frames", "rms", "max", "next best joint");
  std::vector<JsonObject> per_marker;
  for (int s = 0; s < result.marker_set.num_markers(); ++s) {
    const CalibratedMarker& m = result.markers[s];
    const MarkerSpec& spec = result.marker_set.marker(s);
    std::string joints;
    for (const MarkerAttachment& a : spec.attachments) joints += (joints.empty() ? "" : "+") + skeleton.name(a.joint);
    std::string runner = "-";
    if (m.runner_up >= 0) runner = skeleton.name(m.runner_up) + " (" + length(m.runner_up_rms, false) + ")";
    std::printf("%-12s %-14s %7d %s %s  %s\n", TerminalText(m.label).c_str(), TerminalText(joints).c_str(), m.frames,
                length(m.rms, true).c_str(), length(m.max_error, true).c_str(), TerminalText(runner).c_str());
    JsonObject o;
    o.Add("label", m.label).Add("joint", joints).Add("frames", m.frames).Add("rms", m.rms)
        .Add("max_error", m.max_error);
    if (mm > 0.0) o.Add("rms_mm", m.rms * mm);
    per_marker.push_back(o);
  }
  for (const std::string& skipped : result.skipped) std::printf("skipped %s\n", TerminalText(skipped).c_str());
  std::printf("calibrated %d markers over %d samples: RMS %s", result.marker_set.num_markers(), result.samples,
              length(result.rms, false).c_str());
  std::printf(FLAGS_out.empty() ? "\n" : "; wrote %s\n", FLAGS_out.c_str());

  JsonObject report;
  report.Add("motion", FLAGS_motion)
      .Add("markers", FLAGS_markers)
      .Add("out", FLAGS_out)
      .Add("out_subject", FLAGS_out_subject)
      .Add("attach", FLAGS_attach)
      .Add("axes", AxesName(transform.rotation))
      .Add("marker_scale", transform.scale)
      .Add("units", skeleton.unit().name)
      .Add("frame_offset", FLAGS_frame_offset)
      .Add("matched_frames", result.matched_frames)
      .Add("samples", result.samples)
      .Add("rms", result.rms);
  if (mm > 0.0) report.Add("rms_mm", result.rms * mm);
  if (!axis_rms.empty()) {
    std::vector<JsonObject> candidates;
    const std::vector<Eigen::Matrix3d> rotations = AllAxisRotations();
    for (size_t c = 0; c < rotations.size(); ++c) {
      JsonObject o;
      o.Add("axes", AxesName(rotations[c])).Add("rms", axis_rms[c]);
      candidates.push_back(o);
    }
    report.Add("axis_candidates", candidates);
  }
  std::vector<JsonValue> skipped(result.skipped.begin(), result.skipped.end());
  report.Add("skipped", skipped).Add("per_marker", per_marker);
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
    __FILE__, RunCalibrate,
    "motion,markers,out,skeleton,skeleton_units,amc_fps,animation,sample_fps,axes,marker_scale,report"};

}  // namespace mocapsolve
