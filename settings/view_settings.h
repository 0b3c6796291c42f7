// ViewSettings: how `mocapsolve view` shows its files (the characters' clip, the up axis of
// files without a subject, the page's title). Declared once: the CLI's flags and Python's
// view() keywords. The page itself: tasks/view_task.h.
#ifndef MOCAPSOLVE_SETTINGS_VIEW_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_VIEW_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct ViewSettings {
  std::string character_animation;  // The characters' clip (name; "" = each file's first).
  std::string up = "auto";          // Without a subject: auto, x, y or z.
  std::string title;                // "" = the files' names.
};

const OptionGroup<ViewSettings>& ViewSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_VIEW_SETTINGS_H_
