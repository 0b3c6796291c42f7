// Manifests: defaults and per-take overrides resolved over the pipeline's options, paths
// relative to the manifest, and one-line errors naming file, line and field.
#include "batch/manifest.h"

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;


// The take's resolved options, as the record and the key see them.
std::string Resolved(const BatchManifest& manifest, const BatchTake& take) {
  return ResolvedOptionsJson(manifest, take);
}

class ManifestTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(ParsePipelineOptions("{\"filter_levels\": 0, \"gate_torso_deg\": 15, \"reference\": \"tracker\"}",
                                     &pipeline_).ok());
    dir_ = testing::TempPath("m");
    ASSERT_EQ(std::system(("mkdir -p " + dir_ + "/takes").c_str()), 0);
    for (const char* name : {"takes/a.c3d", "takes/b.c3d", "S.json", "C.glb"}) testing::WriteTextFile(dir_ + "/" + name, "x");
  }
  Status Read(const std::string& text, BatchManifest* manifest) {
    testing::WriteTextFile(dir_ + "/M.json", text);
    return ReadManifest(dir_ + "/M.json", pipeline_, manifest);
  }
  BatchOptions pipeline_;
  std::string dir_;
};

TEST_F(ManifestTest, DefaultsOverridesAndRelativePaths) {
  BatchManifest manifest;
  const Status status = Read(
      "{\"defaults\": {\"subject\": \"S.json\", \"characters\": [\"C.glb\"], \"filter_levels\": 1},\n"
      " \"takes\": [{\"markers\": \"takes/a.c3d\"},\n"
      "           {\"name\": \"second\", \"markers\": \"takes/b.c3d\", \"characters\": [], \"filter_levels\": 2,"
      " \"reference\": \"plain\"}]}",
      &manifest);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(manifest.takes.size(), 2u);
  const BatchTake& a = manifest.takes[0];
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.markers, dir_ + "/takes/a.c3d");
  EXPECT_EQ(a.subject, dir_ + "/S.json");
  ASSERT_EQ(a.characters.size(), 1u);
  EXPECT_THAT(Resolved(manifest, a), HasSubstr("\"filter_levels\": 1,"));
  EXPECT_THAT(Resolved(manifest, a), HasSubstr("\"gate_torso_deg\": 15"));  // The pipeline's default.
  const BatchTake& b = manifest.takes[1];
  EXPECT_EQ(b.name, "second");
  EXPECT_TRUE(b.characters.empty());
  EXPECT_THAT(Resolved(manifest, b), HasSubstr("\"filter_levels\": 2,"));
  EXPECT_THAT(Resolved(manifest, b), HasSubstr("\"reference\": \"plain\""));
  // The worker's config holds the given options only (the pipeline treats a set flag
  // unlike its default in places: --solver).
  EXPECT_EQ(GivenOptionsJson(manifest, a), "{\"filter_levels\": 1}");
  EXPECT_EQ(GivenOptionsJson(manifest, b), "{\"filter_levels\": 2, \"reference\": \"plain\"}");
  EXPECT_TRUE(TakeGivesOption(manifest, b, "reference"));
  EXPECT_FALSE(TakeGivesOption(manifest, a, "reference"));
  // Written out and read back: the same takes.
  testing::WriteTextFile(dir_ + "/M2.json", FormatManifest(manifest, pipeline_));
  BatchManifest again;
  ASSERT_TRUE(ReadManifest(dir_ + "/M2.json", pipeline_, &again).ok());
  ASSERT_EQ(again.takes.size(), 2u);
  EXPECT_EQ(Resolved(again, again.takes[1]), Resolved(manifest, b));
  EXPECT_EQ(again.takes[0].characters, a.characters);
  EXPECT_TRUE(again.takes[1].characters.empty());
}

TEST_F(ManifestTest, ErrorsNameFileLineAndField) {
  BatchManifest manifest;
  Status status = Read("{\"takes\": [\n {\"markers\": \"takes/a.c3d\", \"subject\": \"S.json\", \"filter_level\": 1}]}",
                       &manifest);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("M.json:2:"));
  EXPECT_THAT(status.message(), HasSubstr("takes[0]: unknown key 'filter_level'"));
  // A missing input is the take's failure, not the manifest's (the batch runs the others).
  status = Read("{\"takes\": [{\"markers\": \"takes/a.c3d\", \"subject\": \"S.json\"},\n"
                " {\"markers\": \"takes/missing.c3d\", \"subject\": \"S.json\"}]}", &manifest);
  EXPECT_TRUE(status.ok()) << status.message();
  status = Read("{\"takes\": [{\"markers\": \"takes/a.c3d\", \"subject\": \"S.json\", \"filter_levels\": \"2\"}]}",
                &manifest);
  EXPECT_THAT(status.message(), HasSubstr("takes[0].filter_levels: expected a number, got a string"));
  status = Read("{\"takes\": [{\"markers\": \"takes/a.c3d\"}]}", &manifest);
  EXPECT_THAT(status.message(), HasSubstr("missing 'subject'"));
  status = Read("{\"takes\": [{\"markers\": \"takes/a.c3d\", \"subject\": \"S.json\"},"
                " {\"markers\": \"takes/a.c3d\", \"subject\": \"S.json\"}]}", &manifest);
  EXPECT_THAT(status.message(), HasSubstr("the name 'a' is used twice"));
  status = Read("{\"take\": []}", &manifest);
  EXPECT_THAT(status.message(), HasSubstr("unknown key 'take'"));
}

// Names that cannot be a take's folder, or would be one of the batch's own files, are the
// manifest's error, naming the place, the field and the name (escaped: a NUL is shown, not
// a cut).
TEST_F(ManifestTest, RefusesReservedAndImpossibleTakeNames) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"a\\u0000b", "'a\\x00b'"},
      {"tab\\there", "'tab\\x09here'"},
      {"summary.html", "'summary.html' is a file the batch writes"},
      {"summary.json", "'summary.json'"},
      {"summary.csv", "'summary.csv'"},
      {"summary.shard0of2.json", "'summary.shard0of2.json'"},
      {"M.json", "'M.json' is a file the batch writes or reads"},
      {".", "starts with '.'"},
      {"..", "starts with '.'"},
      {"../up", "'../up'"},
      {"a/b", "holds a '/'"},
      {std::string(300, 'n'), "is 300 bytes long"},
  };
  for (const auto& [name, expected] : cases) {
    BatchManifest manifest;
    const Status status = Read("{\"takes\": [{\"markers\": \"takes/a.c3d\", \"subject\": \"S.json\"},\n"
                               " {\"name\": \"" + name + "\", \"markers\": \"takes/b.c3d\", \"subject\": \"S.json\"}]}",
                               &manifest);
    ASSERT_FALSE(status.ok()) << name;
    EXPECT_THAT(status.message(), HasSubstr("M.json:2:2: takes[1].name: the take name")) << name;
    EXPECT_THAT(status.message(), HasSubstr(expected)) << name;
    EXPECT_EQ(status.message().find('\0'), std::string::npos);
    EXPECT_EQ(status.message().find('\n'), std::string::npos);
  }
  // Hostile but usable names pass (the summary's links are made safe instead).
  const std::vector<std::string> usable = {"javascript:alert(1)", "a b#c?d%e", "\\\"q\\\"<x>", "caf\u00e9",
                                           std::string(255, 'n')};
  for (const std::string& name : usable) {
    BatchManifest manifest;
    const Status status = Read("{\"takes\": [{\"name\": \"" + name +
                               "\", \"markers\": \"takes/b.c3d\", \"subject\": \"S.json\"}]}", &manifest);
    EXPECT_TRUE(status.ok()) << name << ": " << status.message();
  }
}

TEST_F(ManifestTest, Glob) {
  BatchManifest manifest;
  ASSERT_TRUE(ManifestFromGlob(dir_ + "/takes/*.c3d", dir_ + "/S.json", {dir_ + "/C.glb"}, pipeline_, &manifest).ok());
  ASSERT_EQ(manifest.takes.size(), 2u);
  EXPECT_EQ(manifest.takes[0].name, "a");
  EXPECT_EQ(manifest.takes[1].name, "b");
  EXPECT_EQ(manifest.takes[1].characters.size(), 1u);
  const Status status = ManifestFromGlob(dir_ + "/takes/*.trc", dir_ + "/S.json", {}, pipeline_, &manifest);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("no file matches"));
}

// Files of the same name in different folders get their folder's name as a prefix (all
// of them, whatever the order), the others keep theirs.
TEST_F(ManifestTest, GlobNamesSameFileNamesByFolder) {
  ASSERT_EQ(std::system(("mkdir -p " + dir_ + "/g/day1 " + dir_ + "/g/day2").c_str()), 0);
  for (const char* name : {"g/day1/walk.c3d", "g/day2/walk.c3d", "g/day2/run.c3d"}) {
    testing::WriteTextFile(dir_ + "/" + name, "x");
  }
  BatchManifest manifest;
  const Status status = ManifestFromGlob(dir_ + "/g/*/*.c3d", dir_ + "/S.json", {}, pipeline_, &manifest);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(manifest.takes.size(), 3u);
  EXPECT_EQ(manifest.takes[0].name, "day1_walk");
  EXPECT_EQ(manifest.takes[1].name, "run");
  EXPECT_EQ(manifest.takes[2].name, "day2_walk");
  // A matched file whose name cannot be a take's: the glob's error, naming the file.
  testing::WriteTextFile(dir_ + "/g/day2/summary.html.c3d", "x");
  const Status bad = ManifestFromGlob(dir_ + "/g/*/*.c3d", dir_ + "/S.json", {}, pipeline_, &manifest);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.message(), "--markers_glob: " + dir_ + "/g/day2/summary.html.c3d: the take name 'summary.html' is a "
                           "file the batch writes or reads itself");
}

// The parser on text alone (the fuzz target's entry): any bytes give a manifest or a
// one-line error.
TEST_F(ManifestTest, ParseManifestTextErrorsAreOneLine) {
  BatchManifest manifest;
  const std::vector<std::string> texts = {"", "{", "[]", "{\"takes\": {}}", "{\"takes\": [1]}", "{\"takes\": [{}]}",
                                         "{\"defaults\": 3, \"takes\": []}"};
  for (const std::string& text : texts) {
    const Status status = ParseManifest(text, "T.json", pipeline_, &manifest);
    ASSERT_FALSE(status.ok()) << text;
    EXPECT_THAT(status.message(), HasSubstr("T.json")) << text;
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace mocapsolve
