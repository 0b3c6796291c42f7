#include "settings/view_settings.h"

namespace mocapsolve {

const OptionGroup<ViewSettings>& ViewSettingOptions() {
  using S = ViewSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::character_animation, "character_animation",
           "The characters' animation to play (name); default: each file's first animation (the one "
           "retarget/pipeline/convert added).")
      .Add(&S::up, "up",
           "Up axis of files without a subject: auto (guessed per file from how its points spread), x, y or z.",
           {"auto", "x", "y", "z"})
      .Add(&S::title, "title", "The page's title (default: the files' names).");
  return *group;
}

}  // namespace mocapsolve
