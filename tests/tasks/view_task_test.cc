// RunView (tasks/view_task.h): the inputs' checks (before the runtime is looked for), the
// scene of files in their own worlds and of a take on its subject, the page in memory. The
// CLI's pages are tested in tests/apps/view_cli_test.cc; Python's view() is compared with
// the CLI's page in tests/python/test_info_view.py.
#include "tasks/view_task.h"

#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/test_support.h"
#include "viewer/view_page.h"

namespace mocapsolve {
namespace {

std::string Good(const std::string& name) { return testing::SourcePath("tests/data/good/" + name); }

TEST(ViewTask, InputsThatGoWithOthersAreChecked) {
  ViewResult result;
  const std::vector<std::pair<ViewInputs, std::string>> cases = {
      {ViewInputs(), "nothing to show: give --markers, --motion and/or --character"},
      {[] { ViewInputs in; in.motion = "m.bvh"; in.repair_report = "r.json"; return in; }(),
       "--repair_report needs --markers"},
      {[] { ViewInputs in; in.motion = "m.bvh"; in.compare = "other.c3d"; return in; }(),
       "--compare=other.c3d: a marker file needs --markers"},
      {[] { ViewInputs in; in.markers = "m.c3d"; in.compare = "other.bvh"; return in; }(),
       "--compare=other.bvh: a motion needs --motion"},
  };
  for (const auto& [inputs, message] : cases) {
    const Status status = RunView(inputs, ViewConfig(), &result);
    EXPECT_EQ(status.message(), message);
  }
}

TEST(ViewTask, FilesInTheirOwnWorldsAndATakeOnItsSubject) {
  std::string runtime;
  if (!FindViewerRuntime(&runtime).ok()) GTEST_SKIP() << "viewer runtime not installed (scripts/viewer_tools.sh)";
  ViewInputs inputs;
  inputs.markers = Good("small.c3d");
  inputs.motion = Good("small.bvh");
  ViewResult own;
  ASSERT_TRUE(RunView(inputs, ViewConfig(), &own).ok());
  EXPECT_EQ(own.scene.markers.size(), 1u);
  EXPECT_EQ(own.scene.skeletons.size(), 1u);
  EXPECT_EQ(own.scene.title, "small + small");
  EXPECT_EQ(own.residual_samples, 0);
  EXPECT_EQ(own.html.rfind("<!DOCTYPE html>", 0), 0u);

  Subject subject;
  ASSERT_TRUE(ReadSubject(Good("subject.json"), &subject).ok());
  inputs.subject = &subject;
  ViewConfig config;
  config.title = "take";
  ViewResult take;
  ASSERT_TRUE(RunView(inputs, config, &take).ok());
  EXPECT_GT(take.residual_samples, 0);
  EXPECT_GT(take.marker_rms_mm, 0.0);
  EXPECT_EQ(take.scene.title, "take");
  EXPECT_NE(take.html, own.html);

  ViewConfig bad_up;
  bad_up.up = "w";
  inputs.subject = nullptr;
  EXPECT_EQ(RunView(inputs, bad_up, &take).message(), "--up=w: expected auto, x, y or z");
}

}  // namespace
}  // namespace mocapsolve
