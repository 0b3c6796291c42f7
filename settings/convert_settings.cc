#include "settings/convert_settings.h"

namespace mocapsolve {

const OptionGroup<ConvertSettings>& ConvertSettingOptions() {
  using S = ConvertSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::scale, "scale", "",
           "Multiply every length (offsets, translations) by this factor, e.g. 5.6444 to turn CMU ASF units into cm.")
      .Add(&S::euler_order, "euler_order",
           "Write every joint's rotation channels in this order (XYZ, XZY, YXZ, YZX, ZXY, ZYX); default: keep each "
           "joint's order from the input.")
      .Add(&S::precision, "precision", "digits", "Significant digits of the written channel values.", 1, 17)
      .Add(&S::clip_name, "clip_name", "glTF output: name of the added animation; FBX output: the take's name.")
      .Add(&S::out_units, "out_units",
           "Marker files: write OUT in this unit (mm, cm, m, in), the coordinates converted; default: IN's unit.");
  return *group;
}

}  // namespace mocapsolve
