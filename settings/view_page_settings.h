// --view: the browser page a command also writes of what it computed (`mocapsolve view`'s
// page). repair, solve, retarget and propagate write one only when asked (PAGE.html);
// pipeline declares its own default, auto: the take folder's view.html when the viewer's
// runtime is installed.
#ifndef MOCAPSOLVE_SETTINGS_VIEW_PAGE_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_VIEW_PAGE_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct ViewPageSetting {
  std::string view;  // "" = none, or the page's path (.html).
};

const OptionGroup<ViewPageSetting>& ViewPageOption();      // "" | PAGE.html.
const OptionGroup<ViewPageSetting>& TakeViewPageOption();  // pipeline: auto | off | PAGE.html.

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_VIEW_PAGE_SETTINGS_H_
