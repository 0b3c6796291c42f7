// A take's subject fitted on the fly, for a take that comes with none (`pipeline
// --subject=auto`, each take of `batch --subject=auto`, Python's pipeline(subject='auto')):
// fit_skeleton's fit (FitSubjectToTake, tasks/fit_skeleton_task.h: the same code, not a
// copy) from the shipped template (pipeline/shipped_templates.h), on the take's labels when
// they are the template's or a shipped protocol map's, else on markers associated with body
// segments from the data; the file's axes from the data either way (kAxesFromData: the feet
// are lowest), its units from the file (from the data when associated). The fitted subject
// must pass fit_skeleton's checks (subject_checks.h: every marker within 15 cm of its bone,
// torso direction within 15 degrees, left/right within 5 %, marker RMS within 25 mm) unless
// settings.check says otherwise; the caller then runs the pipeline with it and writes it
// beside the outputs (AutoSubjectPath), so the next take of that actor can reuse it.
#ifndef MOCAPSOLVE_TASKS_AUTO_SUBJECT_TASK_H_
#define MOCAPSOLVE_TASKS_AUTO_SUBJECT_TASK_H_

#include <string>

#include "io/json_writer.h"
#include "kinematics/status.h"
#include "settings/skeleton_fit_settings.h"
#include "settings/solver_settings.h"
#include "tasks/fit_skeleton_task.h"

namespace mocapsolve {

struct AutoSubjectResult {
  SkeletonFitInputs inputs;  // The template (shipped) and the take, as fitted.
  SkeletonFitResult fit;     // fit.subject: the subject; fit.checks: its checks.
  // How the template met the take: "labels" (the template's own), "labels (map FILE)" (a
  // shipped protocol map), or "association" (segments from the data).
  std::string method;
};

// Fits the subject of the take at `markers_path` (AutoSubjectFitOptions' settings, `solver`
// for its pose solves). Errors (one line, naming the file and "--subject=auto"): the take
// does not read or holds no data, the fit fails (no body found in the points), with
// settings.check "fail" the fitted subject fails a check (the first failed check and its
// figure), or a segment a character needs (the pelvis, a thigh, shin or foot) has no marker
// on it (held_segments.h: the segments and the template's markers for them). The checks
// come first: a fit that failed them may have left a segment's markers elsewhere.
Status FitAutoSubject(const std::string& markers_path, const SkeletonFitSettings& settings,
                      const SolverSettings& solver, AutoSubjectResult* result,
                      const SkeletonFitCallback& callback = nullptr);

// The take report's "subject_fit": fit_skeleton's report (SkeletonFitReportJson: template,
// frames, rounds, RMS, bone scales, checks, the association) with "method".
JsonObject AutoSubjectReport(const AutoSubjectResult& result);

// The console line: "subject: fitted on 508 frames of the take (1 in 5; association,
// template ...): marker RMS 5.4 mm, checks passed, 63.2 s".
std::string AutoSubjectLine(const AutoSubjectResult& result);

// DIR/subject.json: where the fitted subject is written beside the take's outputs.
std::string AutoSubjectPath(const std::string& out_dir);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_AUTO_SUBJECT_TASK_H_
