#include "settings/calibrate_settings.h"

namespace mocapsolve {

const OptionGroup<CalibrateSettings>& CalibrateSettingOptions() {
  using S = CalibrateSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::attach, "attach",
           "auto: each marker rides on the joint in whose frame it moves least; or a marker set .json whose joints "
           "are kept (only offsets re-estimated).")
      .Add(&S::frame_offset, "frame_offset", "frames",
           "Marker frame index = motion frame index + this (CMU 02_01 C3D vs AMC: 0).")
      .Add(&S::min_valid_frames, "min_valid_frames", "frames", "Markers valid in fewer matched frames are left out.",
           1);
  return *group;
}

}  // namespace mocapsolve
