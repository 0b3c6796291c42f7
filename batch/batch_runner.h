// A batch: every take of a manifest through `mocapsolve pipeline`, each in its own worker
// process (worker_process.h), at most `jobs` at a time, resumable.
//
// For each take, in manifest order, when a worker slot is free:
//   1. its key (take_key.h) is computed: input file contents, resolved options, version;
//   2. with DIR/<take>/record.json holding the same key, the take is skipped when the
//      record says "done" and its outputs exist, or says "failed" (unless retry_failed:
//      then it is redone); force redoes every take;
//   3. otherwise the old record (first) and the outputs it lists are removed, the take's
//      options are written as a config file "<position>.json" in the batch's work folder
//      (BatchRunOptions::work_dir, emptied at the start: a killed batch's configs go on
//      the next run), and the worker runs `EXE pipeline --quiet --subject=S --markers=M [--character=C,...]
//      --out_dir=DIR/<take> --config=CONFIG`; the pipeline publishes its outputs
//      together (or none);
//   4. when it ends, its figures are read from DIR/<take>/report.json and the record is
//      written, last, atomically, listing the outputs the worker wrote (the folder's
//      files modified since it started).
// So killing the batch at any moment loses at most the takes in flight (their workers
// die with it) and leaves no partial output: a take's folder has a record matching its
// outputs, or no record (it is redone).
// A take is "done" when the worker exited 0; "gate_failed" when it exited 3 (it ran, its
// outputs are written and kept, its quality gate failed); "failed" otherwise, also when
// one of its inputs is missing, unreadable or not a regular file (then no worker starts;
// the other takes run). A re-run skips failed and gate_failed takes of the same key
// unless retry_failed.
// While it runs, the batch hands its partial result to BatchRunOptions::checkpoint after
// a take ends (at most about once a second, and never more than a tenth of the time), so
// a killed batch leaves a summary of the takes that ended (the others "pending").
#ifndef MOCAPSOLVE_BATCH_BATCH_RUNNER_H_
#define MOCAPSOLVE_BATCH_BATCH_RUNNER_H_

#include <functional>
#include <string>
#include <vector>

#include "batch/manifest.h"
#include "batch/take_record.h"
#include "batch/worker_process.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct BatchResult;

struct BatchRunOptions {
  std::string out_dir;
  int jobs = 1;
  WorkerLimits limits;
  bool force = false;
  bool retry_failed = false;
  std::string executable;   // The mocapsolve binary the workers run.
  std::string version;      // The program version (part of every key).
  int take_threads = 0;     // Each worker's --num_threads unless its options give it (0: the
                            // pipeline's default). Speed only: not part of the key.
  std::string work_dir;     // The takes' config files; emptied at the start, removed at the
                            // end ("" = OUT_DIR/.batch-work).
  std::function<void(const BatchResult&)> checkpoint;  // The partial result (optional).
};

// What the summary shows of a take's record (not its inputs, options or outputs): a batch
// keeps one per take, so it stays small over 10^5 takes.
struct TakeSummary {
  std::string take, key, status, exit, error;  // As in TakeRecord; status "" = not ended.
  int exit_code = 0;
  double wall_seconds = 0.0;
  TakeFigures figures;
};
TakeSummary SummaryOf(TakeRecord&& record);

struct TakeOutcome {
  TakeSummary record;
  bool ran = false;         // False: skipped, the record is the earlier run's.
};

struct BatchProgress {
  int takes = 0, done = 0, failed = 0, skipped = 0, running = 0;  // failed counts gate_failed.
  long frames = 0;          // Frames of the takes that ran and ended.
  double seconds = 0.0;     // Since the batch started.
  double eta_seconds = 0.0; // From the mean wall time of the takes that ran.
};

struct BatchResult {
  std::vector<TakeOutcome> takes;   // In manifest order.
  int done = 0, failed = 0, ran = 0, skipped = 0;  // failed counts gate_failed too.
  int gate_failed = 0;
  double seconds = 0.0;
  double own_seconds = 0.0;         // The batch's own work: keys, records, configs, starts.
};

Status RunBatch(const BatchManifest& manifest, const BatchRunOptions& options,
                const std::function<void(const BatchProgress&)>& progress, BatchResult* result);


}  // namespace mocapsolve

#endif  // MOCAPSOLVE_BATCH_BATCH_RUNNER_H_
