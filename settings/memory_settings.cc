#include "settings/memory_settings.h"

namespace mocapsolve {

const OptionGroup<MemorySettings>& MemoryOption() {
  static const OptionGroup<MemorySettings>* const group =
      &(*new OptionGroup<MemorySettings>())
           .Add(&MemorySettings::memory_mb, "memory_mb", "MB",
                "Refuse, before any work and with the estimate, a take whose whole-clip methods (the pipeline's "
                "stages, the clip solve, the pyramid filter, the Green's function) would need more memory than this "
                "(estimated from the take's frame and marker counts; 0 = no limit).",
                0);
  return *group;
}

}  // namespace mocapsolve
