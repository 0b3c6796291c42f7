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
           1)
      .Add(&S::refit, "refit",
           "Finish the subject (--out_subject) with fit_skeleton --template_subject's refit on the same markers "
           "(its defaults, but every frame, at most 400 spread over the take): bone lengths and offsets fitted "
           "against this project's own per-frame solve, not the given motion's poses (CMU 02_01: marker RMS 11.7 -> "
           "2.7 mm; cross-take leave-one-out median on 02_05 11.3 -> 7.9 mm). Takes a fit's time (1-3 minutes on "
           "02_01). --out's marker set stays the calibration's.");
  return *group;
}

}  // namespace mocapsolve
