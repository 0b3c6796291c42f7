// `evaluate` as one function: marker repair scored on a take, three ways (config.method):
//   repair         the analogue of the thesis' Table 1: the take damaged (as `corrupt`) with
//                  seeds first_seed, first_seed + 1, ... and refilled by every method
//                  (problems/marker_repair/repair_evaluation.h), errors against the solve of
//                  the undamaged markers;
//   leave_one_out  each marker predicted by the solve of the others
//                  (problems/marker_solve/leave_one_out.h), under the protocol
//                  config.evaluate.protocol (tasks/leave_one_out_protocol.h: the subject
//                  from another take, or fitted on the take's first half and the second
//                  half scored), optionally with per-take offset refinement;
//   small_errors   the repair's recall and precision on 1-4 cm jumps and jitter
//                  (problems/marker_repair/small_error_evaluation.h).
// The CLI (apps/evaluate_command.cc: tables on the console, --table_csv, --report) and
// Python's evaluate() both call it.
#ifndef MOCAPSOLVE_TASKS_EVALUATE_TASK_H_
#define MOCAPSOLVE_TASKS_EVALUATE_TASK_H_

#include <functional>
#include <string>
#include <vector>

#include "io/json_writer.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "problems/marker_repair/repair_evaluation.h"
#include "problems/marker_repair/small_error_evaluation.h"
#include "problems/marker_solve/leave_one_out.h"
#include "settings/corruption_settings.h"
#include "settings/evaluate_settings.h"
#include "settings/repair_settings.h"
#include "settings/skeleton_fit_settings.h"
#include "settings/solver_settings.h"

namespace mocapsolve {

struct EvaluateConfig {
  std::string method = "repair";  // repair | leave_one_out | small_errors.
  EvaluateSettings evaluate;       // trials (seeds damage.seed, +1, ...), white_noise_mm.
  RepairSettings repair;
  SolverSettings solver = EvaluateSolverOptions().Defaults();  // mode: leave_one_out's solve.
  CorruptionSettings damage;
  SkeletonFitSettings fit;  // leave_one_out --protocol=time_split: the first half's fit.
  bool keep_predictions = false;  // leave_one_out: fill EvaluateResult::leave_one_out.predicted.
};

struct EvaluateResult {
  // repair: every trial's rows (trial_of_row[i], seed_of_row[i]) and their mean per method.
  std::vector<RepairEvaluationRow> trial_rows;
  std::vector<int> trial_of_row;
  std::vector<uint32_t> seed_of_row;
  std::vector<RepairEvaluationRow> mean_rows;
  // leave_one_out, in skeleton units, over the scored frames of the protocol
  // (leave_one_out_protocol.h; time_split: the second half, markers of the fitted subject,
  // labelled by leave_one_out_labels).
  LeaveOneOutReport leave_one_out;
  std::vector<std::string> leave_one_out_labels;
  SmallErrorRecipe recipe;          // small_errors.
  SmallErrorScore small_errors;
  std::string table_csv;  // What --table_csv writes (repair, leave_one_out; "" otherwise).
  JsonObject report;      // What --report records: mm, cm, degrees, seconds, named so.
};

// Errors: invalid options (naming the option), or a take the solves cannot use (naming
// take.name). progress
// (optional): (done, total) trials or markers.
Status RunEvaluate(const MarkerTake& take, const EvaluateConfig& config,
                   const std::function<void(int done, int total)>& progress, EvaluateResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_EVALUATE_TASK_H_
