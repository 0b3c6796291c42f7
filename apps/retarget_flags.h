// The retargeting knobs `retarget` and `pipeline` share (declared once in
// settings/retarget_settings.h, made flags by main.cc), turned into CharacterRetargetOptions
// in one place.
#ifndef MOCAPSOLVE_APPS_RETARGET_FLAGS_H_
#define MOCAPSOLVE_APPS_RETARGET_FLAGS_H_

#include <gflags/gflags.h>

#include "kinematics/status.h"
#include "settings/retarget_settings.h"
#include "problems/retarget/retarget_character.h"

namespace mocapsolve {

// The declared retarget options (RetargetSolverOptions, RetargetSettingOptions; in
// pipeline --solver and --limit_weight are the marker solver's) and --foot_joints
// (FootJointOption).
RetargetSettings RetargetSettingsFromFlags();
// Those settings as options; reads the --blend_mask and --joint_map files.
Status RetargetOptionsFromFlags(CharacterRetargetOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_RETARGET_FLAGS_H_
