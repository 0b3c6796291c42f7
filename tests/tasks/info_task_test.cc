// RunInfo (tasks/info_task.h): which reader each file goes to and what the result holds;
// the gap runs against the data README's count. The CLI's output and report are the
// printing of this result (tests/apps/gltf_fbx_cli_test.cc and others); Python's info()
// is compared with the CLI's report in tests/python/test_info_view.py.
#include "tasks/info_task.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {

std::string Good(const std::string& name) { return testing::SourcePath("tests/data/good/" + name); }

TEST(InfoTask, EachKindFillsItsParts) {
  InfoResult r;
  ASSERT_TRUE(RunInfo(Good("small.c3d"), InfoConfig(), &r).ok());
  EXPECT_EQ(r.kind, InfoKind::kMarkers);
  EXPECT_FALSE(r.has_skeleton);
  EXPECT_EQ(r.markers.samples, r.markers.frames * static_cast<int>(r.markers.labels.size()));
  EXPECT_EQ(r.report.ToString(false).rfind("{\"file\": ", 0), 0u) << r.report.ToString(false);

  ASSERT_TRUE(RunInfo(Good("small.bvh"), InfoConfig(), &r).ok());
  EXPECT_EQ(r.kind, InfoKind::kMotion);
  EXPECT_TRUE(r.has_skeleton && r.has_motion);
  EXPECT_TRUE(r.animations.empty());
  ASSERT_FALSE(r.skeleton.levels.empty());
  EXPECT_EQ(r.skeleton.levels[0], std::vector<std::string>{r.skeleton.root});
  EXPECT_FALSE(r.skeleton.unit.known());  // A BVH states none ...
  InfoConfig cm;
  cm.skeleton_units = "cm";
  ASSERT_TRUE(RunInfo(Good("small.bvh"), cm, &r).ok());
  EXPECT_EQ(r.skeleton.unit.name, "cm");  // ... unless told.

  ASSERT_TRUE(RunInfo(Good("small.asf"), InfoConfig(), &r).ok());
  EXPECT_EQ(r.kind, InfoKind::kSkeleton);
  EXPECT_FALSE(r.has_motion);

  ASSERT_TRUE(RunInfo(Good("skinned.glb"), InfoConfig(), &r).ok());
  EXPECT_EQ(r.kind, InfoKind::kCharacter);
  EXPECT_EQ(r.skins, 1);
  EXPECT_TRUE(r.has_skeleton);
  EXPECT_FALSE(r.warnings.empty());  // The mesh has no normals: kept for the front ends to show.

  ASSERT_TRUE(RunInfo(Good("small.fbx"), InfoConfig(), &r).ok());
  EXPECT_EQ(r.kind, InfoKind::kFbx);
  EXPECT_TRUE(r.has_skeleton);
}

TEST(InfoTask, ErrorsNameTheFileOrOption) {
  InfoResult r;
  Status status = RunInfo(Good("small.amc"), InfoConfig(), &r);
  EXPECT_NE(status.message().find("an AMC needs its skeleton"), std::string::npos) << status.message();
  InfoConfig config;
  config.animation = "1";
  status = RunInfo(Good("small.bvh"), config, &r);
  EXPECT_NE(status.message().find("applies to .glb/.gltf/.fbx only"), std::string::npos) << status.message();
  status = RunInfo(Good("missing.trc"), InfoConfig(), &r);
  EXPECT_NE(status.message().find("missing.trc"), std::string::npos) << status.message();
}

// shared/data/README.md: nick_freeform_001.c3d has 3874 invalid samples in 511 gap runs.
TEST(InfoTask, GapRunsAreTheReadmesCount) {
  MOCAPSOLVE_DATA_FILE(c3d, "c3d/nick_freeform_001.c3d");
  InfoResult r;
  ASSERT_TRUE(RunInfo(c3d, InfoConfig(), &r).ok());
  EXPECT_EQ(r.markers.gap_runs, 511);
  EXPECT_EQ(r.markers.missing, 3874);
  EXPECT_EQ(r.markers.frames, 1101);
}

}  // namespace
}  // namespace mocapsolve
