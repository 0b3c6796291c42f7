// The damage knobs `corrupt` and `evaluate` share (declared once in
// settings/corruption_settings.h, made flags by main.cc).
#ifndef MOCAPSOLVE_APPS_CORRUPTION_FLAGS_H_
#define MOCAPSOLVE_APPS_CORRUPTION_FLAGS_H_

#include <gflags/gflags.h>

#include "kinematics/status.h"
#include "kinematics/units.h"
#include "settings/corruption_settings.h"
#include "signal/marker_corruption.h"

namespace mocapsolve {

// The declared damage options (CorruptionSettingOptions) as this run's flags made them.
CorruptionSettings CorruptionSettingsFromFlags();

// Distances in mm converted to `unit` (which must be known).
Status CorruptionOptionsFromFlags(const LengthUnit& unit, CorruptionOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_CORRUPTION_FLAGS_H_
