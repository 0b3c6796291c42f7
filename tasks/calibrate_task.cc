#include "tasks/calibrate_task.h"

#include <cmath>
#include <cstdio>

#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "kinematics/quote_token.h"
#include "problems/marker_solve/mean_pose.h"
#include "settings/solver_settings.h"
#include "tasks/console_text.h"

namespace mocapsolve {

Status CalibrateSubject(const Skeleton& skeleton, const Motion& motion,
                        const MarkerTrajectories& file_trajectories,
                        const SubjectCalibrationOptions& options, SubjectCalibration* out) {
  if (options.min_valid_frames < 1) return Status::Error("--min_valid_frames must be >= 1");
  MarkerTrajectories trajectories = file_trajectories;
  // Marker file -> model frame: scale, then axes (given or searched).
  MarkerFileToModel transform;
  if (options.marker_scale > 0.0 && std::isfinite(options.marker_scale)) {
    transform.scale = options.marker_scale;
  } else if (options.marker_scale != 0.0) {
    return Status::Error("--marker_scale must be positive (or 0: from the units)");
  } else {
    Status status = UnitScale(trajectories.unit, skeleton.unit(), &transform.scale);
    if (!status.ok()) {
      return Status::Error(options.markers_name + ": " + status.message() + " (or --skeleton_units)");
    }
  }
  CalibrationOptions calibration;
  calibration.frame_offset = options.frame_offset;
  calibration.min_valid_frames = options.min_valid_frames;
  std::vector<double> axis_rms;
  if (options.axes == "auto") {
    MarkerTrajectories scaled = trajectories;
    MarkerFileToModel scale_only;
    scale_only.scale = transform.scale;
    TransformMarkers(scale_only, skeleton.unit(), &scaled);
    Status status = FindMarkerAxes(skeleton, motion, scaled, calibration, options.attachments,
                                   &transform.rotation, &axis_rms);
    if (!status.ok()) return Status::Error(options.markers_name + ": " + status.message());
  } else {
    Status status = ParseAxes(options.axes, &transform.rotation);
    if (!status.ok()) return status;
  }
  TransformMarkers(transform, skeleton.unit(), &trajectories);
  SubjectCalibration result;
  Status status = CalibrateMarkers(skeleton, motion, trajectories, calibration, options.attachments,
                                   &result.result);
  if (!status.ok()) return Status::Error(options.markers_name + ": " + status.message());
  Subject& subject = result.subject;
  subject.skeleton = skeleton;
  subject.skeleton_path = options.skeleton_path;
  subject.markers = result.result.marker_set;
  subject.axes = AxesName(transform.rotation);
  subject.marker_scale = options.marker_scale;
  if (trajectories.subject_prefixes.size() == 1) subject.label_prefix = trajectories.subject_prefixes[0];
  subject.amc_fps = options.amc_fps;
  subject.mean_pose = MeanPose(skeleton, motion);  // The rest prior's reference.
  result.transform = transform;
  result.axis_rms = std::move(axis_rms);
  *out = std::move(result);
  return Status::Ok();
}

namespace {

// The refit's frames at most (every frame of a shorter take): 02_01's 343 frames fit in
// 1-3 minutes on this machine (the fit, and its second fit with a foot's roll freed).
constexpr int kRefitMaxFrames = 400;

// "LeftArm" or, for a marker on several joints, "LeftArm+LeftForeArm".
std::string AttachedJoints(const Skeleton& skeleton, const MarkerSpec& spec) {
  std::string joints;
  for (const MarkerAttachment& a : spec.attachments) joints += (joints.empty() ? "" : "+") + skeleton.name(a.joint);
  return joints;
}

// The console table: the mapping, one line per marker (joint, frames, RMS, max, next best
// joint), the markers skipped and the overall RMS.
std::string CalibrationTable(const Skeleton& skeleton, const SubjectCalibration& calibration, int frame_offset) {
  const CalibrationResult& result = calibration.result;
  const double mm = skeleton.unit().known() ? skeleton.unit().metres_per_unit * 1000.0 : 0.0;
  const auto length = [&](double value, bool pad) {
    std::string text;
    if (mm > 0.0) {
      AppendF(&text, pad ? "%8.3f mm" : "%.3f mm", value * mm);
    } else {
      AppendF(&text, pad ? "%8.4g units" : "%.4g units", value);
    }
    return text;
  };
  std::string text;
  AppendF(&text, "axes %s, scale %.9g (marker units -> %s), frames %d..%d of the motion (offset %d)\n",
          AxesName(calibration.transform.rotation).c_str(), calibration.transform.scale,
          skeleton.unit().name.c_str(), result.first_motion_frame,
          result.first_motion_frame + result.matched_frames - 1, frame_offset);
  AppendF(&text, "%-12s %-14s %7s %12s %12s  %s\n", "marker", "joint", "frames", "rms", "max", "next best joint");
  for (int s = 0; s < result.marker_set.num_markers(); ++s) {
    const CalibratedMarker& m = result.markers[s];
    const std::string joints = AttachedJoints(skeleton, result.marker_set.marker(s));
    std::string runner = "-";
    if (m.runner_up >= 0) runner = skeleton.name(m.runner_up) + " (" + length(m.runner_up_rms, false) + ")";
    AppendF(&text, "%-12s %-14s %7d %s %s  %s\n", TerminalText(m.label).c_str(), TerminalText(joints).c_str(),
            m.frames, length(m.rms, true).c_str(), length(m.max_error, true).c_str(), TerminalText(runner).c_str());
  }
  for (const std::string& skipped : result.skipped) AppendF(&text, "skipped %s\n", TerminalText(skipped).c_str());
  AppendF(&text, "calibrated %d markers over %d samples: RMS %s", result.marker_set.num_markers(), result.samples,
          length(result.rms, false).c_str());
  return text;
}

JsonObject CalibrationReport(const Skeleton& skeleton, const SubjectCalibration& calibration,
                             const CalibrateSettings& settings) {
  const CalibrationResult& result = calibration.result;
  const double mm = skeleton.unit().known() ? skeleton.unit().metres_per_unit * 1000.0 : 0.0;
  JsonObject report;
  report.Add("attach", settings.attach)
      .Add("axes", AxesName(calibration.transform.rotation))
      .Add("marker_scale", calibration.transform.scale)
      .Add("units", skeleton.unit().name)
      .Add("frame_offset", settings.frame_offset)
      .Add("matched_frames", result.matched_frames)
      .Add("samples", result.samples)
      .Add("rms", result.rms);
  if (mm > 0.0) report.Add("rms_mm", result.rms * mm);
  if (!calibration.axis_rms.empty()) {
    std::vector<JsonObject> candidates;
    const std::vector<Eigen::Matrix3d> rotations = AllAxisRotations();
    for (size_t c = 0; c < rotations.size(); ++c) {
      JsonObject o;
      o.Add("axes", AxesName(rotations[c])).Add("rms", calibration.axis_rms[c]);
      candidates.push_back(o);
    }
    report.Add("axis_candidates", candidates);
  }
  std::vector<JsonObject> per_marker;
  for (int s = 0; s < result.marker_set.num_markers(); ++s) {
    const CalibratedMarker& m = result.markers[s];
    const std::string joints = AttachedJoints(skeleton, result.marker_set.marker(s));
    JsonObject o;
    o.Add("label", m.label).Add("joint", joints).Add("frames", m.frames).Add("rms", m.rms)
        .Add("max_error", m.max_error);
    if (mm > 0.0) o.Add("rms_mm", m.rms * mm);
    per_marker.push_back(o);
  }
  std::vector<JsonValue> skipped(result.skipped.begin(), result.skipped.end());
  report.Add("skipped", skipped).Add("per_marker", per_marker);
  return report;
}

// settings.refit (RunCalibrate): fit_skeleton --template_subject on the calibration's own
// markers, the calibrated subject as the template, every option at its default but the
// frames fitted (--fit_frame_step=1 --fit_max_frames=kRefitMaxFrames).
Status Refit(const MarkerTrajectories& trajectories, const SubjectCalibrationOptions& options,
             CalibrateTaskResult* result) {
  SkeletonFitInputs inputs;
  inputs.templ = result->calibration.subject;
  inputs.template_name = "calibrated subject";
  inputs.markers_path = options.markers_name;
  inputs.trajectories = &trajectories;
  inputs.axes = result->calibration.subject.axes;  // Found by the calibration when "auto".
  inputs.marker_scale = options.marker_scale;
  inputs.amc_fps = options.amc_fps;
  MarkerSolveOptions solve;
  Status status = MarkerSolveOptionsFromSettings(SolverSettings(), inputs.templ.skeleton.unit(), &solve);
  if (!status.ok()) return status;
  SkeletonFitSettings fit_settings;
  fit_settings.check = "warn";  // A failed check keeps the calibrated subject instead.
  // Every frame, up to kRefitMaxFrames spread over the take: a calibration take is short
  // and fitted once per actor, and fit_skeleton's every 4th frame of 02_01 (86 frames)
  // predicted 02_05 worse (cross-take median 9.32 mm against 8.61-8.83 with every 1st-3rd).
  fit_settings.fit_frame_step = 1;
  fit_settings.fit_max_frames = kRefitMaxFrames;
  status = FitSubjectToTake(inputs, fit_settings, solve, &result->refit);
  if (!status.ok()) return status;
  const SkeletonFitResult& fit = result->refit;
  result->refit_kept = fit.checks.ok();
  const double rms = fit.report.rms.empty() ? 0.0 : fit.report.rms.back();
  if (result->refit_kept) {
    result->calibration.subject = fit.subject;  // Its skeleton inline: the lengths are the fit's.
  }
  JsonObject refit;
  refit.Add("kept", result->refit_kept).Add("frames", fit.frames).Add("kept_round", fit.kept_round)
      .Add("rms", rms).Add("checks_passed", fit.checks.ok());
  if (fit.unit_known) refit.Add("rms_mm", rms * fit.mm_per_unit);
  if (!fit.checks.ok()) {
    refit.Add("checks_failed", std::vector<JsonValue>(fit.checks.failures.begin(), fit.checks.failures.end()));
  }
  result->report.Add("refit", refit);
  std::string& line = result->refit_line;
  line = "refit on our own solve (fit_skeleton --template_subject): marker RMS ";
  if (fit.unit_known) {
    AppendF(&line, "%.3f mm", rms * fit.mm_per_unit);
  } else {
    AppendF(&line, "%.4g units", rms);
  }
  AppendF(&line, ", round %d kept%s", fit.kept_round,
          result->refit_kept ? "" : "; its checks failed, the calibrated subject kept");
  return Status::Ok();
}

}  // namespace

Status CheckCalibrateSettings(const CalibrateSettings& settings) {
  Status status = CalibrateSettingOptions().Validate(settings);
  if (!status.ok()) return status;
  if (settings.attach != "auto" && FileExtension(settings.attach) != ".json") {
    return Status::Error("--attach='" + settings.attach + "': expected auto or a marker set .json");
  }
  return Status::Ok();
}

Status RunCalibrate(const Skeleton& skeleton, const Motion& motion, const MarkerTrajectories& trajectories,
                    const CalibrateSettings& settings, SubjectCalibrationOptions options,
                    CalibrateTaskResult* result) {
  Status status = CheckCalibrateSettings(settings);
  if (!status.ok()) return status;
  MarkerSet attachments;
  if (settings.attach != "auto") {
    status = ReadMarkerSet(settings.attach, skeleton, &attachments);
    if (!status.ok()) return status;
  }
  options.frame_offset = settings.frame_offset;
  options.min_valid_frames = settings.min_valid_frames;
  options.attachments = settings.attach == "auto" ? nullptr : &attachments;
  status = CalibrateSubject(skeleton, motion, trajectories, options, &result->calibration);
  if (!status.ok()) return status;
  result->report = CalibrationReport(skeleton, result->calibration, settings);
  result->table = CalibrationTable(skeleton, result->calibration, settings.frame_offset);
  if (settings.refit) {
    status = Refit(trajectories, options, result);
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

}  // namespace mocapsolve
