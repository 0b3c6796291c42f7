// The damage knobs `corrupt` and `evaluate` share (gflags, defined in corruption_flags.cc).
#ifndef MOCAPSOLVE_APPS_CORRUPTION_FLAGS_H_
#define MOCAPSOLVE_APPS_CORRUPTION_FLAGS_H_

#include <gflags/gflags.h>

#include "kinematics/status.h"
#include "kinematics/units.h"
#include "settings/corruption_settings.h"
#include "signal/marker_corruption.h"

DECLARE_int32(corrupt_seed);

namespace mocapsolve {

inline constexpr const char* kCorruptionFlagNames = kCorruptionSettingNames;

// Distances in mm converted to `unit` (which must be known).
Status CorruptionOptionsFromFlags(const LengthUnit& unit, CorruptionOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_CORRUPTION_FLAGS_H_
