#include "settings/take_settings.h"

namespace mocapsolve {

const OptionGroup<TakeSettings>& TakeSettingOptions() {
  using S = TakeSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::take_name, "take_name",
           "The take's name: the characters' new animation (default: the marker file's name without extension).")
      .Add(&S::filter_levels, "filter_levels", "levels",
           "Filter the solved motion: drop the N finest bands of its Laplacian pyramid (as `filter --levels=N`); "
           "0 = no filtering.");
  return *group;
}

}  // namespace mocapsolve
