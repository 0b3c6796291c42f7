// BatchSettings: how `mocapsolve batch` runs its takes (processes at once, threads, limits
// per take, which takes are redone, a shard of the batch, merging the shards' records).
// Declared once; the CLI's flags and Python's batch() keywords. The batch: tasks/batch_task.h.
#ifndef MOCAPSOLVE_SETTINGS_BATCH_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_BATCH_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct BatchSettings {
  int jobs = 0;               // Takes at once; 0 = the cores.
  int take_threads = 0;       // Threads per take; 0 = the cores over jobs, at least 1.
  double take_timeout = 0.0;  // Seconds; 0 = no limit.
  int take_memory_mb = 0;     // RLIMIT_AS per take, MB; 0 = no limit.
  bool force = false;         // Redo every take.
  bool retry_failed = false;  // Redo the takes that failed before.
  bool merge = false;         // Only rebuild the summary from the records.
  std::string shard;          // "i/n": the takes at positions p % n == i; "" = all.
};

const OptionGroup<BatchSettings>& BatchSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_BATCH_SETTINGS_H_
