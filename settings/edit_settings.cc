#include "settings/edit_settings.h"

namespace mocapsolve {

const OptionGroup<EditSettings>& EditSettingOptions() {
  using S = EditSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::frame, "frame", "frames", "The edited frame (0-based).", -1)
      .Add(&S::ik_target, "ik_target",
           "IK edit: JOINT:x,y,z moves JOINT to (x, y, z) (world, skeleton units) at --frame; several targets "
           "separated by ';'.");
  return *group;
}

}  // namespace mocapsolve
