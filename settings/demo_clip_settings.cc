#include "settings/demo_clip_settings.h"

namespace mocapsolve {

const OptionGroup<DemoClipSettings>& DemoClipSettingOptions() {
  using S = DemoClipSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::frames, "frames", "", "Number of frames of the demo clip.", 1, 1000000)
      .Add(&S::fps, "fps", "fps", "Frame rate of the demo clip.", 1e-3, 1e6);
  return *group;
}

}  // namespace mocapsolve
