// The console text of `mocapsolve evaluate`, one table per method: leave_one_out's
// prediction error per marker, small_errors' recall and precision per seed, repair's
// analogue of the thesis' Table 1 (each method's mean over the trials, by damage kind).
// Lengths in mm (skeleton units when the skeleton's unit is unknown), angles in degrees.
#ifndef MOCAPSOLVE_TASKS_EVALUATE_SUMMARY_H_
#define MOCAPSOLVE_TASKS_EVALUATE_SUMMARY_H_

#include <string>

#include "tasks/evaluate_task.h"

namespace mocapsolve {

// What the CLI prints after RunEvaluate (nothing for an unknown method).
std::string EvaluateSummary(const MarkerTake& take, const EvaluateConfig& config, const EvaluateResult& result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_EVALUATE_SUMMARY_H_
