#include "settings/view_page_settings.h"

namespace mocapsolve {

const OptionGroup<ViewPageSetting>& ViewPageOption() {
  static const OptionGroup<ViewPageSetting>* const group = &(*new OptionGroup<ViewPageSetting>()).Add(
      &ViewPageSetting::view, "view",
      "Also write a self-contained browser page (.html, as `mocapsolve view` writes) showing the result: open it "
      "from disk, offline.");
  return *group;
}

const OptionGroup<ViewPageSetting>& TakeViewPageOption() {
  static const OptionGroup<ViewPageSetting>* const group = new OptionGroup<ViewPageSetting>(ViewPageOption().WithDefault(
      "view", "auto",
      "The take's browser page: auto = DIR/view.html when the viewer's runtime is installed (else a warning and no "
      "page); PAGE.html = that page, required (no runtime: an error, nothing written); off = none."));
  return *group;
}

}  // namespace mocapsolve
