// MemorySettings: the memory a run may take for its whole-clip methods. Declared once:
// pipeline (the per-frame stages, the filter, a clip reference), solve (--mode=clip),
// filter (the pyramid) and propagate (the Green's function); each estimates its need
// from the input's frame and marker counts before any work (pipeline/memory_estimate.h)
// and refuses, with the figure, a take over the limit.
#ifndef MOCAPSOLVE_SETTINGS_MEMORY_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_MEMORY_SETTINGS_H_

#include "settings/option.h"

namespace mocapsolve {

struct MemorySettings {
  double memory_mb = 0.0;  // MB (1 MB = 1024 KB); 0 = no limit.
};

const OptionGroup<MemorySettings>& MemoryOption();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_MEMORY_SETTINGS_H_
