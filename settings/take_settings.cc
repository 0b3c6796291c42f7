#include "settings/take_settings.h"

namespace mocapsolve {

const OptionGroup<TakeSettings>& TakeSettingOptions() {
  using S = TakeSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::take_name, "take_name",
           "The take's name: the characters' new animation (default: the marker file's name without extension).")
      .Add(&S::filter_levels, "filter_levels", "levels",
           "Filter the solved motion: drop the N finest bands of its Laplacian pyramid (as `filter --levels=N`); "
           "0 = no filtering.")
      .Add(&S::label, "label",
           "Label the take's points first, as `mocapsolve label` does (raw or unlabelled captures; the label "
           "options set how): auto when the file lacks some of the subject's labels, always (the file's labels "
           "ignored), never (a label the file lacks is an error).",
           {"auto", "never", "always"});
  return *group;
}

}  // namespace mocapsolve
