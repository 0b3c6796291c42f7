#include "apps/retarget_flags.h"

#include "settings/retarget_settings.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "apps/config_flags.h"
#include "apps/option_flags.h"
#include "apps/solver_flags.h"
#include "settings/foot_joint_settings.h"

namespace mocapsolve {

RetargetSettings RetargetSettingsFromFlags() {
  RetargetSettings s;
  // --solver and --limit_weight: retarget's own (RetargetSolverOptions), or in pipeline the
  // marker solver's of the same names (dls by default there too).
  ReadOptionFlags(RetargetSolverOptions(), &s);
  ReadOptionFlags(RetargetSettingOptions(), &s);
  FootJointSettings feet;
  ReadOptionFlags(FootJointOption(), &feet);
  s.foot_joints = feet.foot_joints;
  return s;
}

Status RetargetOptionsFromFlags(CharacterRetargetOptions* options) {
  return RetargetOptionsFromSettings(RetargetSettingsFromFlags(), options);
}

}  // namespace mocapsolve
