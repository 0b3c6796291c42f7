// Manifests: defaults and per-take overrides resolved over the pipeline's options, paths
// relative to the manifest, and one-line errors naming file, line and field.
#include "batch/manifest.h"

#include <cstdio>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;


const JsonNode* Option(const BatchTake& take, const std::string& key) {
  for (const auto& [name, value] : take.options) {
    if (name == key) return &value;
  }
  return nullptr;
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
  EXPECT_EQ(Option(a, "filter_levels")->number, 1);
  EXPECT_EQ(Option(a, "gate_torso_deg")->number, 15);  // The pipeline's default.
  const BatchTake& b = manifest.takes[1];
  EXPECT_EQ(b.name, "second");
  EXPECT_TRUE(b.characters.empty());
  EXPECT_EQ(Option(b, "filter_levels")->number, 2);
  EXPECT_EQ(Option(b, "reference")->string, "plain");
  EXPECT_THAT(OptionsJson(b.options), HasSubstr("\"reference\": \"plain\""));
  // The worker's config holds the given options only (the pipeline treats a set flag
  // unlike its default in places: --solver).
  EXPECT_EQ(OptionsJson(a.given), "{\"filter_levels\": 1}");
  EXPECT_EQ(OptionsJson(b.given), "{\"filter_levels\": 2, \"reference\": \"plain\"}");
  // Written out and read back: the same takes.
  testing::WriteTextFile(dir_ + "/M2.json", FormatManifest(manifest, pipeline_));
  BatchManifest again;
  ASSERT_TRUE(ReadManifest(dir_ + "/M2.json", pipeline_, &again).ok());
  ASSERT_EQ(again.takes.size(), 2u);
  EXPECT_EQ(OptionsJson(again.takes[1].options), OptionsJson(b.options));
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
  status = Read("{\"takes\": [{\"markers\": \"takes/a.c3d\", \"subject\": \"S.json\"},\n"
                " {\"markers\": \"takes/missing.c3d\", \"subject\": \"S.json\"}]}", &manifest);
  EXPECT_THAT(status.message(), HasSubstr("M.json:2:2: takes[1]: markers:"));
  EXPECT_THAT(status.message(), HasSubstr("missing.c3d"));
  status = Read("{\"takes\": [{\"markers\": \"takes/a.c3d\", \"subject\": \"S.json\", \"filter_levels\": \"2\"}]}",
                &manifest);
  EXPECT_THAT(status.message(), HasSubstr("takes[0].filter_levels: expected a number, got a string"));
  status = Read("{\"takes\": [{\"markers\": \"takes/a.c3d\"}]}", &manifest);
  EXPECT_THAT(status.message(), HasSubstr("missing 'subject'"));
  status = Read("{\"takes\": [{\"markers\": \"takes/a.c3d\", \"subject\": \"S.json\"},"
                " {\"markers\": \"takes/a.c3d\", \"subject\": \"S.json\"}]}", &manifest);
  EXPECT_THAT(status.message(), HasSubstr("the name 'a' is used twice"));
  status = Read("{\"takes\": [{\"name\": \"../up\", \"markers\": \"takes/a.c3d\", \"subject\": \"S.json\"}]}",
                &manifest);
  EXPECT_THAT(status.message(), HasSubstr("not a plain folder name"));
  status = Read("{\"take\": []}", &manifest);
  EXPECT_THAT(status.message(), HasSubstr("unknown key 'take'"));
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

}  // namespace
}  // namespace mocapsolve
