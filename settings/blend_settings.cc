#include "settings/blend_settings.h"

namespace mocapsolve {

const OptionGroup<BlendSettings>& BlendSettingOptions() {
  using S = BlendSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::transition, "transition",
           "START:END of the transition window, in frames of --a (0-based), or in seconds of --a with an 's' suffix "
           "on both (1.5s:2s).")
      .Add(&S::b_start, "b_start", "frames",
           "Frame of --a at which --b's frame 0 lies (-1: the transition start). If --b ends before --a, --b lies "
           "inside --a and the blend returns to --a.", -1)
      .Add(&S::blend_levels, "blend_levels", "", "Pyramid levels of the multires blend (0 = as many as fit).", 0, 30);
  return *group;
}

}  // namespace mocapsolve
