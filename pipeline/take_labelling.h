// Labelling a take for a subject: every point of a marker file (labels ignored; any order,
// ghosts, dropouts) given one of the subject's markers or left unlabelled
// (problems/marker_label/marker_labeller.h), and the file rewritten with the subject's
// labels. Used by `mocapsolve label` (tasks/label_task.h) and by the pipeline when a take's
// labels do not match its subject (TakeSettings::label, settings/take_settings.h).
#ifndef MOCAPSOLVE_PIPELINE_TAKE_LABELLING_H_
#define MOCAPSOLVE_PIPELINE_TAKE_LABELLING_H_

#include <string>
#include <vector>

#include "io/json_writer.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "problems/marker_label/marker_labeller.h"
#include "settings/label_settings.h"
#include "settings/solver_settings.h"

namespace mocapsolve {

struct TakeLabelling {
  // The take labelled: one column per marker of the subject (its labels), then the points
  // left unlabelled as "*1".."*K"; samples as the file holds them (axes, unit, residuals),
  // the file's rate and first frame.
  MarkerTrajectories markers;
  // [frame][file column]: the subject's marker given to that sample, -1 = none.
  std::vector<std::vector<int>> marker_of_sample;
  LabellingResult details;
  int points = 0;        // Valid samples in the file (every column).
  double seconds = 0.0;  // The labelling alone.
};

// Labels every point of `file` for `subject` (its axes and marker scale map the file onto
// the skeleton); `solver` is the per-frame solve's options. Errors, one line naming `name`:
// a take without frames or points; points that match no placement of the subject (with
// the best match found).
Status LabelTakeForSubject(const Subject& subject, const MarkerTrajectories& file, const std::string& name,
                           const LabelSettings& settings, const SolverSettings& solver,
                           const LabelProgress& progress, TakeLabelling* labelling);

// What a report records of a labelling: frames, points, per label the samples labelled,
// swaps avoided and re-acquisitions, the body's acquisitions, the time.
JsonObject LabellingReport(const Subject& subject, const TakeLabelling& labelling);

// The labels of the subject's marker set (its label prefix allowed) that `file` has no
// column for: `--label=auto` labels a take when this is not empty.
std::vector<std::string> SubjectLabelsMissing(const Subject& subject, const MarkerTrajectories& file);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_TAKE_LABELLING_H_
