#include "apps/repair_flags.h"

#include <glog/logging.h>

#include "apps/option_flags.h"

#include "apps/solver_flags.h"

namespace mocapsolve {

RepairSettings RepairSettingsFromFlags() {
  RepairSettings settings;
  // main.cc checked every declared option's value as it parsed the command line.
  const Status status = ReadOptionFlags(RepairSettingOptions(), &settings);
  CHECK(status.ok()) << status.message();
  return settings;
}

Status RepairOptionsFromFlags(const Skeleton& skeleton, RepairOptions* options) {
  return RepairOptionsFromSettings(RepairSettingsFromFlags(), SolverSettingsFromFlags(), skeleton, options);
}

}  // namespace mocapsolve
