// --view=PAGE.html (settings/view_page_settings.h, declared by each command that offers it)
// with which repair, solve, retarget and propagate also write a `mocapsolve view` page of
// what they computed, through the command's FileTransaction like their other outputs.
#ifndef MOCAPSOLVE_APPS_VIEW_FLAGS_H_
#define MOCAPSOLVE_APPS_VIEW_FLAGS_H_

#include <string>
#include <vector>

#include "kinematics/status.h"
#include "viewer/view_page.h"
#include "viewer/view_scene.h"

namespace mocapsolve {

// The page this run asked for ("" = none): the running command's --view.
std::string ViewFlag();

// Checks --view before any work: it must end in .html (case-insensitive), must not name
// one of `inputs`, and the viewer's runtime must be installed (the error says to run
// scripts/viewer_tools.sh): a page asked for and not written is an error, never a warning.
Status CheckViewFlag(const std::vector<std::string>& inputs);

// Writes --view (if given) from the scene the make() callback builds (only called then).
template <typename MakeScene>
Status WriteViewFlag(MakeScene make) {
  const std::string page = ViewFlag();
  if (page.empty()) return Status::Ok();
  ViewScene scene;
  Status status = make(&scene);
  if (!status.ok()) return Status::Error("--view=" + page + ": " + status.message());
  return WriteViewPage(page, scene);
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_VIEW_FLAGS_H_
