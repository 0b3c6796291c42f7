// Edit files (io/edit_file.h): the two layouts, and annotated bad files
// (tests/data/bad/bad_edit_*.json, whose "comment" reads "expect-error: LINE:COL: text").
#include <filesystem>

#include <gtest/gtest.h>

#include "io/edit_file.h"
#include "io/json_reader.h"
#include "io/motion_file.h"
#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

TEST(EditFileTest, OneEdit) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::vector<EditFileEntry> edits;
  const Status status = ParseEditFile(
      R"({"format": "mocapsolve.edit", "version": 1, "comment": "raise the arm",
          "frame": 12, "joints": {"LeftArm": {"rotation_offset_deg": [0, 0, 90]},
                                  "Spine": {"rotation_offset_deg": [10, 0, 0]}},
          "root_translation_offset": [1, -2, 3]})", "one.json", skeleton, &edits);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(edits.size(), 1u);
  EXPECT_EQ(edits[0].frame, 12);
  ASSERT_EQ(edits[0].rotation_offsets_rad.size(), 2u);
  EXPECT_EQ(edits[0].rotation_offsets_rad[0].first, skeleton.FindJoint("LeftArm"));
  EXPECT_NEAR(edits[0].rotation_offsets_rad[0].second.z(), kPi / 2, 1e-15);
  EXPECT_EQ(edits[0].root_translation_offset, Eigen::Vector3d(1, -2, 3));
  EXPECT_EQ(edits[0].where, "one.json:2:20");
}

TEST(EditFileTest, SeveralEdits) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::vector<EditFileEntry> edits;
  const Status status = ParseEditFile(
      R"({"edits": [{"frame": 3, "root_translation_offset": [0, 1, 0]},
                    {"frame": 9, "joints": {"Hips": {"rotation_offset_deg": [0, 5, 0]}}}]})",
      "two.json", skeleton, &edits);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(edits.size(), 2u);
  EXPECT_EQ(edits[1].frame, 9);
  EXPECT_TRUE(edits[0].rotation_offsets_rad.empty());
}

TEST(EditFileTest, ErrorsNameTheField) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::vector<EditFileEntry> edits;
  const struct {
    const char* text;
    const char* expected;
  } cases[] = {
      {R"({"frame": 1})", "e.json:1:1: edit: changes nothing"},
      {R"({"joints": {"Hips": {"rotation_offset_deg": [0, 0, 1]}}})", "e.json:1:1: frame: missing"},
      {R"({"frame": 1, "root_translation_offset": [0, "a", 0]})", "root_translation_offset[1]: expected a number"},
      {R"({"frame": 1, "joints": {"Hips": {"rotation_offset": [0, 0, 1]}}})", "joints.Hips.rotation_offset: unknown key"},
      {R"({"frame": 1, "frames": 2})", "e.json:1:24: frames: unknown key"},
      {R"({"edits": [{"frame": 1, "root_translation_offset": [0, 1, 0]}, {"frame": 1, "root_translation_offset": [0, 1, 0]}]})",
       "edits[1].frame: frame 1 is edited twice"},
      {R"({"edits": []})", "edits: expected at least one edit"},
      {R"({"format": "mocapsolve.markerset", "frame": 1})", "format: expected \"mocapsolve.edit\""},
      {R"([1, 2])", "top level: expected an object"},
      {R"({"frame": 1,})", "e.json:1:13"},
  };
  for (const auto& c : cases) {
    const Status status = ParseEditFile(c.text, "e.json", skeleton, &edits);
    ASSERT_FALSE(status.ok()) << c.text;
    EXPECT_NE(status.message().find(c.expected), std::string::npos) << status.message();
    EXPECT_EQ(status.message().find('\n'), std::string::npos);
  }
}

// Each tests/data/bad/bad_edit_*.json carries "comment": "expect-error: LINE:COL: text";
// reading it must fail with the one line "PATH:LINE:COL: text...". Also used by the CLI
// test (propagate_cli_test.cc).
TEST(EditFileTest, AnnotatedBadFiles) {
  MOCAPSOLVE_DATA_FILE(path, "bvh/16_15.bvh");  // The bad files name 16_15's joints.
  Skeleton skeleton;
  ASSERT_TRUE(ReadSkeletonFile(path, &skeleton).ok());
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testing::SourcePath("tests/data/bad"))) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("bad_edit_", 0) != 0 || entry.path().extension() != ".json") continue;
    const std::string file = entry.path().string();
    SCOPED_TRACE(file);
    JsonNode root;
    ASSERT_TRUE(ReadJsonFile(file, &root).ok());
    const JsonNode* comment = root.Find("comment");
    ASSERT_TRUE(comment != nullptr && comment->is_string());
    const std::string tag = "expect-error: ";
    ASSERT_EQ(comment->string.rfind(tag, 0), 0u);
    const std::string expected = file + ":" + comment->string.substr(tag.size());
    std::vector<EditFileEntry> edits;
    const Status status = ReadEditFile(file, skeleton, &edits);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.message().rfind(expected, 0), 0u) << status.message();
    EXPECT_EQ(status.message().find('\n'), std::string::npos);
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

}  // namespace
}  // namespace mocapsolve
