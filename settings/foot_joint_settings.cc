#include "settings/foot_joint_settings.h"

namespace mocapsolve {

const OptionGroup<FootJointSettings>& FootJointOption() {
  static const OptionGroup<FootJointSettings>* const group =
      &(*new OptionGroup<FootJointSettings>())
           .Add(&FootJointSettings::foot_joints, "foot_joints",
                "Comma-separated foot joints for contacts (default: names with foot, toe or ankle).");
  return *group;
}

}  // namespace mocapsolve
