#include "tasks/auto_subject_task.h"

#include <cstdio>

#include "problems/marker_solve/held_segments.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

Status FitAutoSubject(const std::string& markers_path, const SkeletonFitSettings& settings,
                      const SolverSettings& solver, AutoSubjectResult* result, const SkeletonFitCallback& callback) {
  *result = AutoSubjectResult();
  SkeletonFitInputs& inputs = result->inputs;
  inputs.markers_path = markers_path;
  inputs.axes = kAxesFromData;
  Status status = LoadSkeletonFitTemplate("", "", "", "", &inputs);
  MarkerSolveOptions solve_options;
  if (status.ok()) status = MarkerSolveOptionsFromSettings(solver, inputs.templ.skeleton.unit(), &solve_options);
  if (!status.ok()) return status;
  status = FitSubjectToTake(inputs, settings, solve_options, &result->fit, callback);
  if (!status.ok()) return Status::Error("--subject=auto: " + status.message());
  const SkeletonFitResult& fit = result->fit;
  result->method = fit.associated                      ? "association"
                   : fit.template_labels_map.empty() ? "labels"
                                                     : "labels (map " + fit.template_labels_map + ")";
  if (!fit.checks.ok() && settings.check == "fail") {
    const size_t more = fit.checks.failures.size() - 1;
    return Status::Error(markers_path + ": --subject=auto: the subject fitted from the shipped template (" +
                         result->method + ") fails its check: " + fit.checks.failures[0] +
                         (more > 0 ? " (and " + std::to_string(more) + " more)" : "") +
                         "; nothing written (give a subject, or --check=warn to use it anyway)");
  }
  // A segment the character needs that no marker observes (a set too sparse for it): a
  // character would deliver it at the template's rest, whatever the take did. Asked
  // after the checks: a failed fit leaves markers anywhere (squat renamed, its arm
  // taken for the chest: 67.8 mm, and no marker on the left foot it has), so its failed
  // check is the error, not the segment.
  const std::vector<std::string> missing =
      MissingSegments(fit.subject.skeleton, fit.subject.markers, inputs.templ.markers);
  if (!missing.empty()) {
    std::string names;
    for (const std::string& segment : missing) names += (names.empty() ? "" : ", ") + segment;
    return Status::Error(markers_path + ": --subject=auto: no marker of the take observes " + names +
                         "; a character needs the pelvis and both legs; nothing written");
  }
  return Status::Ok();
}

JsonObject AutoSubjectReport(const AutoSubjectResult& result) {
  JsonObject json = SkeletonFitReportJson(result.inputs, result.fit);
  json.Add("method", result.method);
  return json;
}

std::string AutoSubjectLine(const AutoSubjectResult& result) {
  const SkeletonFitResult& fit = result.fit;
  char line[512];
  const std::string stride = fit.frame_stride > 1 ? "1 in " + std::to_string(fit.frame_stride) + "; " : "";
  std::snprintf(line, sizeof line, "subject: fitted on %d frames of the take (%s%s, template %s): marker RMS %.1f mm, "
                "torso %.1f deg, checks %s, %.1f s\n", fit.frames, stride.c_str(), result.method.c_str(),
                result.inputs.template_name.c_str(), fit.checks.rms_mm, fit.checks.torso_error_mean_deg,
                fit.checks.ok() ? "passed" : ("failed: " + fit.checks.failures[0]).c_str(), fit.seconds);
  std::string text = line;
  if (!fit.held.tops.empty()) {
    std::string tops;
    for (const std::string& top : fit.held.tops) tops += (tops.empty() ? "" : ", ") + top;
    text += "subject: no marker observes " + tops + " (" + std::to_string(fit.held.joints) +
            " joints): held at the template's mean pose\n";
  }
  return text;
}

std::string AutoSubjectPath(const std::string& out_dir) {
  return (out_dir.empty() ? "" : out_dir + "/") + "subject.json";
}

}  // namespace mocapsolve
