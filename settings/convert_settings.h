// ConvertSettings: the options of `mocapsolve convert` (besides the clip's delivery,
// settings/delivery_settings.h): BVH output's scale, channel order and digits, the name of
// the clip added to a glTF/FBX character, and marker files' output unit. Declared once.
#ifndef MOCAPSOLVE_SETTINGS_CONVERT_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_CONVERT_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct ConvertSettings {
  double scale = 1.0;                 // BVH output: every length times this.
  std::string euler_order;            // BVH/FBX output: XYZ, ..., ZYX; "" = each joint's own.
  int precision = 6;                  // BVH output: significant digits.
  std::string clip_name = "mocapsolve";
  std::string out_units;              // Marker output: mm, cm, m, in; "" = IN's.
};

const OptionGroup<ConvertSettings>& ConvertSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_CONVERT_SETTINGS_H_
