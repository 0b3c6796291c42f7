#include "apps/view_flags.h"

#include "apps/common_flags.h"
#include "io/motion_file.h"

DEFINE_string(view, "", "Also write a self-contained browser page (.html, as `mocapsolve view` "
              "writes) showing the result: open it from disk, offline.");

namespace mocapsolve {

Status CheckViewFlag(const std::vector<std::string>& inputs) {
  if (FLAGS_view.empty()) return Status::Ok();
  if (!IsTextOutputPath(FLAGS_view, ".html")) return Status::Error("--view=" + FLAGS_view + ": expected an .html page");
  for (const std::string& input : inputs) {
    Status status = CheckNotAnInput(FLAGS_view, input);
    if (!status.ok()) return status;
  }
  // The page was asked for: a missing viewer runtime is an error now, before any work,
  // not a page silently missing at the end.
  std::string runtime;
  Status status = FindViewerRuntime(&runtime);
  if (!status.ok()) return Status::Error("--view=" + FLAGS_view + ": " + status.message());
  return Status::Ok();
}

}  // namespace mocapsolve
