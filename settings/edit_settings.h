// EditSettings: where a pose edit is made: the edited frame and, for an IK edit, the
// targets there. Declared once: distance (the frame its distances are from) and propagate.
#ifndef MOCAPSOLVE_SETTINGS_EDIT_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_EDIT_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct EditSettings {
  int frame = -1;         // The edited frame (0-based); -1 = not given.
  std::string ik_target;  // JOINT:x,y,z[;...] (world, skeleton units) at `frame`.
};

const OptionGroup<EditSettings>& EditSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_EDIT_SETTINGS_H_
