// Marker set files: exact round trips (single-bone and blended markers), unit handling,
// and one-line errors naming the file, line, marker and field for bad inputs.
#include "io/marker_set_file.h"

#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "kinematics/demo_character.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

void ExpectSameMarkerSets(const MarkerSet& a, const MarkerSet& b, double tolerance) {
  ASSERT_EQ(a.num_markers(), b.num_markers());
  for (int m = 0; m < a.num_markers(); ++m) {
    EXPECT_EQ(a.label(m), b.label(m));
    ASSERT_EQ(a.marker(m).attachments.size(), b.marker(m).attachments.size()) << a.label(m);
    for (size_t k = 0; k < a.marker(m).attachments.size(); ++k) {
      const MarkerAttachment& x = a.marker(m).attachments[k];
      const MarkerAttachment& y = b.marker(m).attachments[k];
      EXPECT_EQ(x.joint, y.joint) << a.label(m);
      EXPECT_NEAR(x.weight, y.weight, tolerance) << a.label(m);
      EXPECT_NEAR((x.offset - y.offset).norm(), 0.0, tolerance) << a.label(m);
    }
    EXPECT_EQ(a.marker(m).solve_weight, b.marker(m).solve_weight) << a.label(m);
  }
}

// The demo skeleton with its unit replaced (e.g. unknown, as a BVH reads back).
Skeleton WithUnit(const Skeleton& skeleton, const LengthUnit& unit) {
  std::vector<JointSpec> joints;
  for (int j = 0; j < skeleton.num_joints(); ++j) joints.push_back(skeleton.joint(j));
  Skeleton result;
  EXPECT_TRUE(Skeleton::Create(joints, skeleton.end_sites(), unit, &result).ok());
  return result;
}

MarkerSet BlendedSet(const Skeleton& skeleton) {
  std::vector<MarkerSpec> specs = {
      {"LKNE", {{skeleton.FindJoint("LeftUpLeg"), 0.25, {1.0 / 3.0, -40.0, 5.5}},
                {skeleton.FindJoint("LeftLeg"), 0.75, {0.1, 2.0, 5.0}}}},
      {"C7", {{skeleton.FindJoint("Neck"), 1.0, {0.0, 1e-17, -7.25}}}},
      {"we\"ird\\label", {{0, 2.0, {-987654321.12345678, 3e-300, 12345.678901234567}}}},
  };
  MarkerSet set;
  EXPECT_TRUE(MarkerSet::Create(skeleton, specs, &set).ok());
  return set;
}

TEST(MarkerSetFile, RoundTripIsExact) {
  const Skeleton skeleton = MakeDemoSkeleton();
  for (const MarkerSet& original : {MakeSyntheticMarkerSet(skeleton, 3, 11), BlendedSet(skeleton)}) {
    const std::string path = testing::TempPath("set.json");
    ASSERT_TRUE(WriteMarkerSet(path, skeleton, original, "demo character").ok());
    MarkerSet read;
    const Status status = ReadMarkerSet(path, skeleton, &read);
    ASSERT_TRUE(status.ok()) << status.message();
    ExpectSameMarkerSets(original, read, 0.0);  // Round-trip exact number printing.
  }
}

// Learned solve weights (version 2) round trip exactly; a set without them is still
// written as version 1, and version 1 files (no solve_weight) read as weight 1.
TEST(MarkerSetFile, SolveWeightsRoundTripAndVersionOneStillReads) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const MarkerSet plain = BlendedSet(skeleton);
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < plain.num_markers(); ++m) specs.push_back(plain.marker(m));
  specs[0].solve_weight = 0.123456789012345678;
  specs[2].solve_weight = 1e-3;
  MarkerSet weighted;
  ASSERT_TRUE(MarkerSet::Create(skeleton, specs, &weighted).ok());
  const std::string text = FormatMarkerSet(skeleton, weighted);
  EXPECT_THAT(text, HasSubstr("\"version\": 2"));
  EXPECT_THAT(text, HasSubstr("\"solve_weight\": 0.12345678901234568"));
  MarkerSet read;
  Status status = ParseMarkerSet(text, "w.json", skeleton, &read);
  ASSERT_TRUE(status.ok()) << status.message();
  ExpectSameMarkerSets(weighted, read, 0.0);
  EXPECT_EQ(read.marker(1).solve_weight, 1.0);
  const std::string v1 = FormatMarkerSet(skeleton, plain);
  EXPECT_THAT(v1, HasSubstr("\"version\": 1"));
  EXPECT_THAT(v1, ::testing::Not(HasSubstr("solve_weight")));
  ASSERT_TRUE(ParseMarkerSet(v1, "v1.json", skeleton, &read).ok());
  for (int m = 0; m < read.num_markers(); ++m) EXPECT_EQ(read.marker(m).solve_weight, 1.0);
  // A weight out of range names the marker and the field.
  std::string bad = text;
  bad.replace(bad.find("0.12345678901234568"), 19, "-1");
  status = ParseMarkerSet(bad, "bad.json", skeleton, &read);
  EXPECT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("bad.json"));
  EXPECT_THAT(status.message(), HasSubstr("solve_weight: expected in (0, 1e6]"));
  specs[1].solve_weight = 0.0;
  EXPECT_FALSE(MarkerSet::Create(skeleton, specs, &weighted).ok());
}

TEST(MarkerSetFile, FormatIsDocumentedShape) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const std::string text = FormatMarkerSet(skeleton, BlendedSet(skeleton), "walk.bvh");
  EXPECT_THAT(text, HasSubstr("\"format\": \"mocapsolve.markerset\""));
  EXPECT_THAT(text, HasSubstr("\"version\": 1"));
  EXPECT_THAT(text, HasSubstr("\"units\": \"cm\""));
  EXPECT_THAT(text, HasSubstr("\"skeleton\": \"walk.bvh\""));
  EXPECT_THAT(text, HasSubstr("{\"label\": \"C7\", \"attachments\": [{\"joint\": \"Neck\", \"weight\": 1, "
                              "\"offset\": [0, 1e-17, -7.25]}]}"));
  // An empty set is valid too.
  MarkerSet empty, read;
  ASSERT_TRUE(ParseMarkerSet(FormatMarkerSet(skeleton, empty), "e.json", skeleton, &read).ok());
  EXPECT_EQ(read.num_markers(), 0);
}

TEST(MarkerSetFile, UnitsAreConvertedOrChecked) {
  const Skeleton cm = MakeDemoSkeleton();
  const std::string mm_file =
      R"({"format": "mocapsolve.markerset", "version": 1, "units": "mm",
          "markers": [{"label": "A", "attachments": [{"joint": "Hips", "offset": [10, 20, -30]}]}]})";
  MarkerSet set;
  ASSERT_TRUE(ParseMarkerSet(mm_file, "mm.json", cm, &set).ok());
  EXPECT_NEAR((set.marker(0).attachments[0].offset - Eigen::Vector3d(1, 2, -3)).norm(), 0.0, 1e-15);
  // Skeleton without a unit (BVH): offsets are taken as they are.
  const Skeleton unknown = WithUnit(cm, LengthUnit());
  ASSERT_TRUE(ParseMarkerSet(mm_file, "mm.json", unknown, &set).ok());
  EXPECT_EQ(set.marker(0).attachments[0].offset, Eigen::Vector3d(10, 20, -30));
  // ASF units by their name.
  const Skeleton asf = WithUnit(cm, AcclaimLength(0.45));
  ASSERT_TRUE(ParseMarkerSet(FormatMarkerSet(cm, set), "cm.json", asf, &set).ok());
  EXPECT_NEAR(set.marker(0).attachments[0].offset.x(), 10.0 / (2.54 / 0.45), 1e-12);
  // A unit nobody knows against a known skeleton unit is an error.
  std::string text = mm_file;
  text.replace(text.find("\"mm\""), 4, "\"furlong\"");
  const Status status = ParseMarkerSet(text, "f.json", cm, &set);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("f.json:1:"));
  EXPECT_THAT(status.message(), HasSubstr("furlong"));
}

struct BadCase {
  const char* name;
  std::string json;
  const char* expected;  // Substring of the message.
};

TEST(MarkerSetFile, BadInputsGiveOneLineErrorsNamingTheField) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const std::string head = R"({"format": "mocapsolve.markerset", "version": 1, "units": "cm", "markers": [)";
  const std::string good = R"({"label": "A", "attachments": [{"joint": "Hips", "offset": [1, 2, 3]}]})";
  const std::vector<BadCase> cases = {
      {"unknown joint", head + good + ",\n" + R"({"label": "LFWT", "attachments": [{"joint": "Pelvis", "offset": [1, 2, 3]}]}]})",
       "bad.json:2:45: markers[1]: 'LFWT': attachments[0].joint: unknown joint 'Pelvis'"},
      {"two-number offset", head + R"({"label": "B", "attachments": [{"joint": "Hips", "offset": [1, 2]}]}]})",
       "markers[0]: 'B': attachments[0].offset: expected an array of 3 numbers"},
      {"string in offset", head + R"({"label": "B", "attachments": [{"joint": "Hips", "offset": [1, "2", 3]}]}]})",
       "attachments[0].offset[1]: expected number, got string"},
      {"negative weight", head + R"({"label": "B", "attachments": [{"joint": "Hips", "weight": -1, "offset": [1, 2, 3]}]}]})",
       "attachments[0].weight: expected in [0, 1e6]"},
      // Found by tests/apps/malformed_input_sweep_cli_test.cc: an offset of -1e308 went through
      // FK and came out as a marker beyond float range in the C3D writer, whose error named
      // the output, not the marker set.
      {"huge offset", head + R"({"label": "B", "attachments": [{"joint": "Hips", "offset": [1, -1e308, 3]}]}]})",
       "attachments[0].offset[1]: beyond +-1e9"},
      {"huge weight", head + R"({"label": "B", "attachments": [{"joint": "Hips", "weight": 1e308, "offset": [1, 2, 3]}]}]})",
       "attachments[0].weight: expected in [0, 1e6]"},
      {"zero weights", head + R"({"label": "B", "attachments": [{"joint": "Hips", "weight": 0, "offset": [1, 2, 3]}]}]})",
       "weights sum to zero"},
      {"no attachments", head + R"({"label": "B", "attachments": []}]})", "attachments: empty"},
      {"duplicate label", head + good + "," + good + "]}", "markers[1]: 'A': label: duplicate"},
      {"empty label", head + R"({"label": "", "attachments": []}]})", "label: empty"},
      {"typo key", head + R"({"label": "B", "attachments": [{"joint": "Hips", "ofset": [1, 2, 3]}]}]})",
       "unknown key 'ofset'"},
      {"missing offset", head + R"({"label": "B", "attachments": [{"joint": "Hips"}]}]})", "missing \"offset\""},
      {"joint index", head + R"({"label": "B", "attachments": [{"joint": 3, "offset": [1, 2, 3]}]}]})",
       "attachments[0].joint: expected string, got number"},
      {"wrong format", R"({"format": "other", "version": 1, "units": "cm", "markers": []})", "format: expected"},
      {"version 3", R"({"format": "mocapsolve.markerset", "version": 3, "units": "cm", "markers": []})",
       "version: expected 1"},
      {"no units", R"({"format": "mocapsolve.markerset", "version": 1, "markers": []})", "missing \"units\""},
      {"markers object", R"({"format": "mocapsolve.markerset", "version": 1, "units": "cm", "markers": {}})",
       "markers: expected array, got object"},
      {"top-level array", "[]", "expected a marker set object"},
      {"syntax", head + good + " " + good + "]}", "bad.json:1:"},
      {"truncated", head + good, "end of file"},
      {"binary", std::string("\x00\x01\xff", 3), "bad.json:1:1"},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name);
    MarkerSet set;
    const Status status = ParseMarkerSet(c.json, "bad.json", skeleton, &set);
    ASSERT_FALSE(status.ok());
    EXPECT_THAT(status.message(), HasSubstr(c.expected));
    EXPECT_EQ(status.message().rfind("bad.json:", 0), 0u) << status.message();
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
  }
}

TEST(MarkerSetFile, ReadErrorsNameThePath) {
  const Skeleton skeleton = MakeDemoSkeleton();
  MarkerSet set;
  Status status = ReadMarkerSet("/nonexistent/set.json", skeleton, &set);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("/nonexistent/set.json"));
  // The corpus files the CLI test also runs.
  for (const char* name : {"bad_markerset_unknown_joint.json", "bad_markerset_offset.json",
                           "bad_markerset_syntax.json", "bad_markerset_huge_offset.json"}) {
    const std::string path = testing::SourcePath(std::string("tests/data/bad/") + name);
    status = ReadMarkerSet(path, skeleton, &set);
    ASSERT_FALSE(status.ok()) << name;
    EXPECT_THAT(status.message(), HasSubstr(name));
  }
}

TEST(MarkerSetFile, WriteIsAtomicAndChecksJoints) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const std::string path = testing::TempPath("nested/dir/set.json");
  EXPECT_FALSE(WriteMarkerSet(path, skeleton, BlendedSet(skeleton)).ok());  // No such directory.
  std::ifstream in(path);
  EXPECT_FALSE(in.good());
}

}  // namespace
}  // namespace mocapsolve
