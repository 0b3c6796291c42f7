#include "apps/view_flags.h"

#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "io/motion_file.h"
#include "settings/view_page_settings.h"

namespace mocapsolve {

std::string ViewFlag() {
  ViewPageSetting setting;
  ReadOptionFlags(ViewPageOption(), &setting);
  return setting.view;
}

Status CheckViewFlag(const std::vector<std::string>& inputs) {
  const std::string page = ViewFlag();
  if (page.empty()) return Status::Ok();
  if (!IsTextOutputPath(page, ".html")) return Status::Error("--view=" + page + ": expected an .html page");
  for (const std::string& input : inputs) {
    Status status = CheckNotAnInput(page, input);
    if (!status.ok()) return status;
  }
  // The page was asked for: a missing viewer runtime is an error now, before any work,
  // not a page silently missing at the end.
  std::string runtime;
  Status status = FindViewerRuntime(&runtime);
  if (!status.ok()) return Status::Error("--view=" + page + ": " + status.message());
  return Status::Ok();
}

}  // namespace mocapsolve
