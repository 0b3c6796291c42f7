// The marker-repair knobs `repair` and `evaluate` share (gflags, defined in
// repair_flags.cc), turned into RepairOptions in one place.
#ifndef MOCAPSOLVE_APPS_REPAIR_FLAGS_H_
#define MOCAPSOLVE_APPS_REPAIR_FLAGS_H_

#include <gflags/gflags.h>

#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "settings/repair_settings.h"
#include "problems/marker_repair/marker_repair.h"

namespace mocapsolve {

// The declared repair options (RepairSettingOptions) as this run's flags made them.
RepairSettings RepairSettingsFromFlags();

// Thresholds in cm and degrees are converted with the skeleton's unit (which must be
// known). The naive solve takes the solver flags.
Status RepairOptionsFromFlags(const Skeleton& skeleton, RepairOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_REPAIR_FLAGS_H_
