// The console lines of `mocapsolve pipeline` after a take (RunTakePipeline,
// pipeline/take_pipeline.h): the speed, each stage's time, the marker residuals before and
// after repair, and each character's vertex error and foot skating.
#ifndef MOCAPSOLVE_TASKS_TAKE_SUMMARY_H_
#define MOCAPSOLVE_TASKS_TAKE_SUMMARY_H_

#include <string>

#include "pipeline/take_pipeline.h"

namespace mocapsolve {

std::string TakeSummary(const TakeInputs& inputs, const TakeResult& result);

// The quality gate's failures, "; "-separated ("" when it passed), and on a failed marker
// check a second line: the markers to blame and what to try (pipeline/gate_blame.h).
std::string TakeGateFailures(const TakeResult& result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_TAKE_SUMMARY_H_
