// `repair` as one function (thesis chapter 3; problems/marker_repair/marker_repair.h): a
// take in, the repaired markers, the motion solved from them and the report out. The CLI
// (apps/repair_command.cc: flags, files, progress) and Python's repair() both call it, so
// the options' set-up (the subject's mean pose as the rest prior's reference included)
// and the report are made in one place.
#ifndef MOCAPSOLVE_TASKS_REPAIR_TASK_H_
#define MOCAPSOLVE_TASKS_REPAIR_TASK_H_

#include <vector>

#include <Eigen/Core>

#include "io/json_writer.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "problems/marker_repair/marker_repair.h"
#include "settings/repair_settings.h"
#include "settings/solver_settings.h"

namespace mocapsolve {

struct RepairConfig {
  RepairSettings repair;
  SolverSettings solver = RepairSolverOptions().Defaults();  // The solver options without --mode.
};

struct RepairResult {
  MarkerTrajectories markers;  // The take's file with the repaired samples, in its own axes
                               // and unit (what --out_markers writes).
  std::vector<std::vector<Eigen::Vector3d>> repaired;  // [frame][marker], skeleton frame and units.
  Motion motion;               // Solved from the repaired markers, at the file's frame rate.
  RepairReport details;        // In skeleton units.
  int rewritten_samples = 0;   // Samples of `markers` that differ from the file.
  int unlabelled_removed_samples = 0;  // Unlabelled points moved under a marker's label.
  // What --report records (and Python's repair() returns): mm, seconds, frames, named so.
  JsonObject report;
};

// The repair options made from `config` for the take's skeleton: validated (a one-line
// error naming the option), thresholds converted from cm/degrees, the rest prior's
// reference the take's mean pose.
Status RepairOptionsForTake(const MarkerTake& take, const RepairConfig& config, RepairOptions* options);

// Errors: invalid options (naming the option), or a take the repair cannot solve (naming
// take.name).
Status RunRepair(const MarkerTake& take, const RepairConfig& config, const RepairProgress& progress,
                 RepairResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_REPAIR_TASK_H_
