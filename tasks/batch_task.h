// `batch` as one function: `pipeline` over many takes (a manifest, or a glob of marker files
// with one subject and characters), each take in its own worker process running
// `executable pipeline` (batch/batch_runner.h), resumable by each take's key; or, with
// merge, the summary rebuilt from the takes' records. The CLI (apps/batch_command.cc:
// flags, the progress line) and Python's batch() both call it.
#ifndef MOCAPSOLVE_TASKS_BATCH_TASK_H_
#define MOCAPSOLVE_TASKS_BATCH_TASK_H_

#include <functional>
#include <string>
#include <vector>

#include "batch/batch_runner.h"
#include "kinematics/status.h"
#include "settings/batch_settings.h"

namespace mocapsolve {

struct BatchInputs {
  std::string manifest;                 // Batch manifest (.json); or
  std::string markers_glob;             // one take per matching marker file, all with
  std::string subject;                  // this subject and
  std::vector<std::string> characters;  // these characters.
  std::string out_dir;
  // Pipeline options for every take, a JSON object ({"formats": "glb,fbx"}; "" = none):
  // they replace the manifest's defaults, a take's own value still wins.
  std::string pipeline_options;
  std::string write_manifest;  // Also write the batch's manifest here (alone: without out_dir).
  BatchSettings settings;      // Jobs, threads, limits, force/retry, merge, shard.
  std::string executable;      // The mocapsolve CLI the workers run.
  std::string version;         // Its version (part of every take's key).
};

struct BatchTaskResult {
  enum class Kind { kRan, kMerged, kManifestOnly, kEmptyShard };
  Kind kind = Kind::kRan;
  BatchResult result;
  int shard = 0, shards = 1;
  std::string summary_base;  // "summary" or "summary.shard<i>of<n>" (DIR/<base>.json, .csv).
  int manifest_takes = 0;    // Takes in the written manifest (kManifestOnly).
};

// Errors: bad flags, a bad manifest (naming the file and field), an output that is an
// input; a failed take is not an error (result.failed counts them).
Status RunBatchTask(const BatchInputs& inputs, const std::function<void(const BatchProgress&)>& progress,
                    BatchTaskResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_BATCH_TASK_H_
