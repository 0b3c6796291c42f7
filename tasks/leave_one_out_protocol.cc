#include "tasks/leave_one_out_protocol.h"

#include <utility>
#include <vector>

#include "io/marker_file.h"

#include "problems/marker_solve/marker_observations.h"
#include "settings/skeleton_fit_settings.h"
#include "tasks/fit_skeleton_task.h"

namespace mocapsolve {
namespace {

constexpr int kMinSplitFrames = 20;

// The subject the take was read with (TakeForSubject's inverse, as far as a fit needs it).
Subject TakeSubject(const MarkerTake& take) {
  Subject subject;
  subject.name = "--subject";
  subject.skeleton = take.skeleton;
  subject.markers = take.markers;
  subject.mean_pose = take.mean_pose;
  subject.axes = AxesName(take.transform.rotation);
  subject.marker_scale = take.transform.scale;
  return subject;
}

Status TimeSplit(const MarkerTake& take, const SolverSettings& solver, const SkeletonFitSettings& fit_settings,
                 MarkerTake* scored, JsonObject* report) {
  const int frames = take.trajectories.num_frames();
  if (frames < 2 * kMinSplitFrames) {
    return Status::Error(take.name + ": --protocol=time_split needs at least " + std::to_string(2 * kMinSplitFrames) +
                         " frames (has " + std::to_string(frames) + ")");
  }
  const int half = frames / 2;
  // The fit sees the first half only: a copy of those frames, nothing of the second.
  const MarkerTrajectories first = TrajectoryFrames(take.trajectories, 0, half);
  SkeletonFitInputs inputs;
  inputs.templ = TakeSubject(take);
  inputs.template_name = "--subject";
  inputs.markers_path = take.name + " (frames 0-" + std::to_string(half - 1) + ")";
  inputs.axes = inputs.templ.axes;
  inputs.marker_scale = inputs.templ.marker_scale;
  inputs.trajectories = &first;
  MarkerSolveOptions solve_options;
  Status status = MarkerSolveOptionsFromSettings(solver, take.skeleton.unit(), &solve_options);
  if (!status.ok()) return status;
  SkeletonFitResult fit;
  status = FitSubjectToTake(inputs, fit_settings, solve_options, &fit);
  if (!status.ok()) return status;
  status = TakeForSubject(fit.subject, TrajectoryFrames(take.trajectories, half, frames - half),
                          take.name + " (frames " + std::to_string(half) + "-" + std::to_string(frames - 1) + ")",
                          scored);
  if (!status.ok()) return status;
  const double rms = fit.report.rms.empty() ? 0.0 : fit.report.rms.back();
  report->Add("protocol", "time_split").Add("fit_frames", half).Add("scored_first_frame", half)
      .Add("scored_frames", frames - half).Add("fit_rms_mm", rms * fit.mm_per_unit)
      .Add("fit_markers", fit.subject.markers.num_markers()).Add("fit_checks_passed", fit.checks.ok());
  return Status::Ok();
}

}  // namespace

Status LeaveOneOutProtocolTake(const MarkerTake& take, const std::string& protocol, const SolverSettings& solver,
                               const SkeletonFitSettings& fit, MarkerTake* scored, JsonObject* report) {
  if (protocol == "time_split") return TimeSplit(take, solver, fit, scored, report);
  if (protocol != "cross_take") return Status::Error("--protocol: expected cross_take or time_split, got '" + protocol + "'");
  *scored = take;
  report->Add("protocol", "cross_take").Add("scored_first_frame", 0)
      .Add("scored_frames", static_cast<int>(take.observed.size()));
  return Status::Ok();
}

Status TemplateTakeForSubject(const Subject& templ, MarkerTrajectories trajectories, const std::string& name,
                              MarkerTake* take) {
  Subject present = templ;
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < templ.markers.num_markers(); ++m) {
    if (trajectories.FindMarker(templ.label_prefix + templ.markers.label(m)) >= 0 ||
        trajectories.FindMarker(templ.markers.label(m)) >= 0) {
      specs.push_back(templ.markers.marker(m));
    }
  }
  if (specs.empty()) return Status::Error(name + ": no marker of the subject's marker set is in the take");
  Status status = MarkerSet::Create(templ.skeleton, std::move(specs), &present.markers);
  if (status.ok()) status = TakeForSubject(present, std::move(trajectories), name, take);
  if (!status.ok()) return status;
  take->markers = templ.markers;
  take->observed.clear();
  return Status::Ok();
}

Status ReadTimeSplitTake(const std::string& subject_path, const std::string& markers_path, const std::string* axes,
                         const double* marker_scale, MarkerTake* take) {
  if (subject_path.empty()) return Status::Error("--protocol=time_split needs --subject (the fit's template)");
  Subject templ;
  Status status = ReadSubject(subject_path, &templ);
  if (!status.ok()) return status;
  if (axes != nullptr) templ.axes = *axes;
  if (marker_scale != nullptr) templ.marker_scale = *marker_scale;
  MarkerTrajectories trajectories;
  status = ReadMarkerFile(markers_path, &trajectories);
  if (status.ok()) status = RequireMarkerData(markers_path, trajectories);
  return status.ok() ? TemplateTakeForSubject(templ, std::move(trajectories), markers_path, take) : status;
}

}  // namespace mocapsolve
