#include "settings/batch_settings.h"

namespace mocapsolve {

const OptionGroup<BatchSettings>& BatchSettingOptions() {
  using S = BatchSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::jobs, "jobs", "processes", "Takes run at the same time, each in its own process; 0 = the number of cores.",
           0)
      .Add(&S::take_threads, "take_threads", "threads",
           "Threads of each take (the pipeline's --num_threads, unless the manifest gives it); 0 = the cores over "
           "--jobs, at least 1. Speed only: results and keys do not depend on it.", 0)
      .Add(&S::take_timeout, "take_timeout", "s",
           "A take running longer than this (seconds) is killed and listed as failed ('timeout'); 0 = no limit.", 0.0)
      .Add(&S::take_memory_mb, "take_memory_mb", "MB",
           "Address-space limit of each take's process (MB, RLIMIT_AS); a take exceeding it fails; 0 = no limit.", 0)
      .Add(&S::force, "force", "Redo every take, finished or not.")
      .Add(&S::retry_failed, "retry_failed",
           "Redo the takes that failed in an earlier run (otherwise they are skipped and stay listed as failed).")
      .Add(&S::merge, "merge",
           "Build DIR/summary.json/.csv from the takes' records alone (after the shards ran): the manifest's takes (a "
           "take without a record is 'missing'), or without --manifest every DIR/*/record.json.")
      .Add(&S::shard, "shard",
           "Run shard i/n of the batch only (0 <= i < n): the takes at manifest positions p with p % n == i; its "
           "summary is DIR/summary.shard<i>of<n>.json/.csv (then `batch --merge`). Default under a Slurm job array: "
           "SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN / SLURM_ARRAY_TASK_COUNT.");
  return *group;
}

}  // namespace mocapsolve
