// FootJointSettings: which joints are feet, for foot contacts (planted feet kept in place).
// Declared once: propagate (--keep_contacts), retarget and pipeline (planted feet).
#ifndef MOCAPSOLVE_SETTINGS_FOOT_JOINT_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_FOOT_JOINT_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct FootJointSettings {
  std::string foot_joints;  // Comma-separated; "" = the joints named with foot, toe or ankle.
};

const OptionGroup<FootJointSettings>& FootJointOption();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_FOOT_JOINT_SETTINGS_H_
