// `label` as one function: a subject and a take of unlabelled points (any labels, any
// order, ghosts, dropouts) in; the take with the subject's labels, the per-label counts
// and the report out (problems/marker_label/marker_labeller.h). The CLI
// (apps/label_command.cc) calls it; the benchmarks score it on scrambled takes.
#ifndef MOCAPSOLVE_TASKS_LABEL_TASK_H_
#define MOCAPSOLVE_TASKS_LABEL_TASK_H_

#include <string>
#include <vector>

#include "io/json_writer.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "problems/marker_label/marker_labeller.h"
#include "settings/label_settings.h"
#include "settings/repair_settings.h"
#include "settings/solver_settings.h"

namespace mocapsolve {

struct LabelConfig {
  LabelSettings label;
  SolverSettings solver = RepairSolverOptions().Defaults();  // The per-frame solve's options.
};

struct LabelResult {
  // The take labelled: one column per marker of the subject (its labels), then the points
  // left unlabelled as "*1".."*K"; samples as the file holds them (axes, unit, residuals),
  // the file's rate and first frame.
  MarkerTrajectories markers;
  // [frame][file column]: the subject's marker given to that sample, -1 = none.
  std::vector<std::vector<int>> marker_of_sample;
  LabellingResult details;
  double seconds = 0.0;  // The labelling alone (not reading or writing).
  JsonObject report;     // What --report records: per label labelled, swaps avoided, re-acquisitions.
  std::string summary;   // The console text (no final newline).
};

// Every point of `file` (labels ignored) labelled for `subject` (its axes and marker scale
// map the file onto the skeleton). Errors, one line naming `name`: a take without frames
// or points; points that match no placement of the subject (with the best match found).
Status RunLabel(const Subject& subject, const MarkerTrajectories& file, const std::string& name,
                const LabelConfig& config, const LabelProgress& progress, LabelResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_LABEL_TASK_H_
