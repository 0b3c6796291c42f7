#include "settings/frame_limit_settings.h"

namespace mocapsolve {

const OptionGroup<FrameLimitSettings>& FrameLimitOption() {
  static const OptionGroup<FrameLimitSettings>* const group =
      &(*new OptionGroup<FrameLimitSettings>())
           .Add(&FrameLimitSettings::max_frames, "max_frames", "frames",
                "Work on the input's first N frames only (0 = all).", 0);
  return *group;
}

}  // namespace mocapsolve
