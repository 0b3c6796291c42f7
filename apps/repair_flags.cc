#include "apps/repair_flags.h"

#include "apps/option_flags.h"

#include "apps/solver_flags.h"

namespace mocapsolve {

RepairSettings RepairSettingsFromFlags() {
  RepairSettings settings;
  ReadOptionFlags(RepairSettingOptions(), &settings);
  return settings;
}

Status RepairOptionsFromFlags(const Skeleton& skeleton, RepairOptions* options) {
  return RepairOptionsFromSettings(RepairSettingsFromFlags(), SolverSettingsFromFlags(), skeleton, options);
}

}  // namespace mocapsolve
