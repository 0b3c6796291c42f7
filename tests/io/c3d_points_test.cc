// The vendor conventions of io/c3d_points.h on C3D files written here in the vendors'
// layouts (no real file is copied in): duplicate labels (Motion Analysis), model outputs
// (Vicon Nexus POINT:ANGLES, ..., Plug-in Gait virtual points), two subjects with label
// prefixes (a person and a prop), labels with spaces and lower case, > 255 points.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "io/c3d_points.h"
#include "io/c3d_reader.h"
#include "io/c3d_writer.h"
#include "io/marker_file.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using testing::RunCli;
using testing::TempPath;
using testing::WriteTextFile;

// A C3D in a vendor's layout: Intel float storage, `labels` as given (duplicates
// allowed) in POINT:LABELS, LABELS2, ... (255 per parameter), and any other string-array
// parameters ("POINT:ANGLES", "SUBJECTS:LABEL_PREFIXES"). Point m in frame f is at
// (1000 + m, 10 f, 5), so a test can tell which file point a marker came from; point
// `gap_point` is missing in frame 1.
struct VendorC3d {
  std::vector<std::string> labels;
  std::vector<std::pair<std::string, std::vector<std::string>>> strings;  // "GROUP:NAME" -> values.
  int num_frames = 3;
  int gap_point = 0;

  static double X(int point) { return 1000.0 + point; }

  std::string Build() const {
    std::vector<std::pair<std::string, std::vector<std::string>>> all;
    for (size_t begin = 0, chunk = 1; begin < labels.size() || chunk == 1; begin += 255, ++chunk) {
      const auto end = labels.begin() + std::min(labels.size(), begin + 255);
      all.emplace_back(chunk == 1 ? "POINT:LABELS" : "POINT:LABELS" + std::to_string(chunk),
                       std::vector<std::string>(labels.begin() + begin, end));
    }
    all.insert(all.end(), strings.begin(), strings.end());
    std::map<std::string, int> groups = {{"POINT", 1}};
    std::string records;
    const auto record = [&](int group_id, const std::string& name, const std::string& body) {
      records.push_back(static_cast<char>(name.size()));
      records.push_back(static_cast<char>(group_id));
      records += name;
      const std::uint16_t next = static_cast<std::uint16_t>(2 + body.size() + 1);
      records.append(reinterpret_cast<const char*>(&next), 2);
      records += body;
      records.push_back('\0');  // No description.
    };
    const auto group = [&](const std::string& name) {
      if (!groups.count(name)) groups.emplace(name, static_cast<int>(groups.size()) + 1);
      return groups[name];
    };
    record(-1, "POINT", "");
    const auto int16 = [](std::uint16_t v) { return std::string("\x02\x00", 2) + std::string(reinterpret_cast<char*>(&v), 2); };
    const auto float32 = [](float v) { return std::string("\x04\x00", 2) + std::string(reinterpret_cast<char*>(&v), 4); };
    record(1, "USED", int16(static_cast<std::uint16_t>(labels.size())));
    record(1, "SCALE", float32(-1.0f));
    record(1, "RATE", float32(100.0f));
    record(1, "UNITS", std::string("\xff\x01\x02", 3) + "mm");
    const size_t data_start_at = records.size() + 2 + 10 + 2 + 2;  // Value offset of DATA_START.
    record(1, "DATA_START", int16(0));
    for (const auto& [key, values] : all) {
      const std::string group_name = key.substr(0, key.find(':'));
      const bool is_new = !groups.count(group_name);
      const int id = group(group_name);
      if (is_new) record(-id, group_name, "");
      size_t width = 1;
      for (const std::string& v : values) width = std::max(width, v.size());
      std::string body = {static_cast<char>(-1), 2, static_cast<char>(width), static_cast<char>(values.size())};
      for (std::string v : values) body += v.append(width - v.size(), ' ');
      record(id, key.substr(key.find(':') + 1), body);
    }
    records += std::string("\0\0", 2);  // End of the section.
    const size_t blocks = (4 + records.size() + 511) / 512;
    const std::uint16_t data_start = static_cast<std::uint16_t>(2 + blocks);
    std::memcpy(&records[data_start_at], &data_start, 2);
    std::string file(512, '\0');
    file[0] = 2;
    file[1] = 0x50;
    const auto put16 = [&](size_t at, std::uint16_t v) { std::memcpy(&file[at], &v, 2); };
    const auto putf = [&](size_t at, float v) { std::memcpy(&file[at], &v, 4); };
    put16(2, static_cast<std::uint16_t>(labels.size()));
    put16(6, 1);
    put16(8, static_cast<std::uint16_t>(num_frames));
    putf(12, -1.0f);
    put16(16, data_start);
    putf(20, 100.0f);
    std::string section = {1, 0x50, static_cast<char>(blocks), 84};
    section += records;
    section.resize(blocks * 512, '\0');
    file += section;
    for (int f = 0; f < num_frames; ++f) {
      for (int m = 0; m < static_cast<int>(labels.size()); ++m) {
        const bool gap = m == gap_point && f == 1;
        for (float v : {static_cast<float>(X(m)), 10.0f * f, 5.0f, gap ? -1.0f : 0.0f}) {
          file.append(reinterpret_cast<const char*>(&v), 4);
        }
      }
    }
    file.resize((file.size() + 511) / 512 * 512, '\0');
    return file;
  }
};

Status Read(const VendorC3d& fixture, MarkerTrajectories* t, C3dFileInfo* info = nullptr,
            const C3dReadOptions& options = {}) {
  return ParseC3d(fixture.Build(), "vendor.c3d", t, info, options);
}

// The file point a marker column came from (its x coordinate, frame 0).
int SourcePoint(const MarkerTrajectories& t, int column) {
  return static_cast<int>(t.position(0, column).x() - 1000.0 + 0.5);
}

void ExpectOneLineError(const Status& status, const std::string& part) {
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
  EXPECT_EQ(status.message().rfind("vendor.c3d: ", 0), 0u) << status.message();
  EXPECT_NE(status.message().find(part), std::string::npos) << "expected '" << part << "' in: " << status.message();
}

// ---------------------------------------------------------------------------------------
// Duplicate labels (Motion Analysis EVa/Cortex).

TEST(C3dPoints, DuplicateLabelsAreNumberedWithOneWarning) {
  VendorC3d fixture;
  fixture.labels = {"LASI", "RKNE", "LKNE", "RKNE", "LKNE", "RKNE", "RKNE#3"};
  MarkerTrajectories t;
  C3dFileInfo info;
  const Status status = Read(fixture, &t, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(t.labels(), (std::vector<std::string>{"LASI", "RKNE", "LKNE", "RKNE#2", "LKNE#2", "RKNE#4", "RKNE#3"}));
  for (int m = 0; m < t.num_markers(); ++m) EXPECT_EQ(SourcePoint(t, m), m);
  ASSERT_EQ(info.warnings.size(), 1u);
  const std::string& warning = info.warnings[0];
  EXPECT_EQ(warning.rfind("vendor.c3d: POINT:LABELS: 2 labels are used more than once", 0), 0u) << warning;
  EXPECT_NE(warning.find("'RKNE' (points 2, 4, 6 read as RKNE, RKNE#2, RKNE#4)"), std::string::npos) << warning;
  EXPECT_NE(warning.find("'LKNE' (points 3, 5 read as LKNE, LKNE#2)"), std::string::npos) << warning;
}

TEST(C3dPoints, UniqueLabelsGiveNoWarning) {
  VendorC3d fixture;
  fixture.labels = {"LASI", "RASI"};
  MarkerTrajectories t;
  C3dFileInfo info;
  ASSERT_TRUE(Read(fixture, &t, &info).ok());
  EXPECT_TRUE(info.warnings.empty());
  EXPECT_EQ(t.model_outputs, nullptr);
}

// ---------------------------------------------------------------------------------------
// Model outputs (Vicon Nexus, Plug-in Gait).

VendorC3d NexusFixture() {
  VendorC3d fixture;
  fixture.labels = {"Pat:LASI",       "Pat:LKneeAngles", "Pat:RASI",  "Pat:LHipForce",     "Pat:PELO",
                    "Pat:CentreOfMass", "Pat:LKneeMoment", "Pat:Vmax", "Pat:LAbsAnkleAngle", "Pat:RKNE",
                    "Pat:LNormalisedGRF", "Pat:RHipPower", "*13"};
  fixture.strings = {{"POINT:ANGLES", {"Pat:LKneeAngles", "Pat:LAbsAnkleAngle"}},
                     {"POINT:FORCES", {"Pat:LHipForce", "Pat:LNormalisedGRF"}},
                     {"POINT:MOMENTS", {"Pat:LKneeMoment"}},
                     {"POINT:POWERS", {"Pat:RHipPower"}},
                     {"POINT:SCALARS", {"Vmax"}},  // Listed without the prefix.
                     {"SUBJECTS:NAMES", {"Pat"}},
                     {"SUBJECTS:LABEL_PREFIXES", {"Pat:"}}};
  fixture.gap_point = 1;  // A model output with a gap.
  return fixture;
}

TEST(C3dPoints, ModelOutputsAreSetApartByListAndByName) {
  MarkerTrajectories t;
  C3dFileInfo info;
  const Status status = Read(NexusFixture(), &t, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(t.labels(), (std::vector<std::string>{"Pat:LASI", "Pat:RASI", "Pat:RKNE", "*13"}));
  EXPECT_EQ(SourcePoint(t, 1), 2);
  EXPECT_EQ(SourcePoint(t, 3), 12);
  EXPECT_EQ(t.subject_prefixes, std::vector<std::string>{"Pat:"});
  EXPECT_EQ(info.model_output_points, 9);
  ASSERT_EQ(info.warnings.size(), 1u);
  EXPECT_NE(info.warnings[0].find("9 of 13 points are model outputs"), std::string::npos) << info.warnings[0];
  ASSERT_NE(t.model_outputs, nullptr);
  const ModelOutputPoints& outputs = *t.model_outputs;
  EXPECT_EQ(outputs.points.labels(),
            (std::vector<std::string>{"Pat:LKneeAngles", "Pat:LHipForce", "Pat:PELO", "Pat:CentreOfMass",
                                      "Pat:LKneeMoment", "Pat:Vmax", "Pat:LAbsAnkleAngle", "Pat:LNormalisedGRF",
                                      "Pat:RHipPower"}));
  EXPECT_EQ(outputs.kinds, (std::vector<std::string>{"ANGLES", "FORCES", "", "", "MOMENTS", "SCALARS", "ANGLES",
                                                     "FORCES", "POWERS"}));
  EXPECT_EQ(outputs.points.num_frames(), 3);
  EXPECT_FALSE(outputs.points.valid(1, 0));  // The gap stays a gap.
  EXPECT_EQ(outputs.points.position(2, 0), Eigen::Vector3d(1001.0, 20.0, 5.0));
}

TEST(C3dPoints, IncludeModelOutputsReadsEveryPointAsAMarker) {
  MarkerTrajectories t;
  C3dFileInfo info;
  C3dReadOptions options;
  options.include_model_outputs = true;
  ASSERT_TRUE(Read(NexusFixture(), &t, &info, options).ok());
  EXPECT_EQ(t.num_markers(), 13);
  EXPECT_EQ(t.model_outputs, nullptr);
  EXPECT_TRUE(info.warnings.empty());
}

TEST(C3dPoints, PluginGaitNamesAndOrdinaryMarkers) {
  std::string kind;
  for (const char* name : {"PELO", "LFEA", "RTOP", "HEDL", "TRXO", "CentreOfMass", "CentreOfMassFloor"}) {
    EXPECT_TRUE(IsPluginGaitOutputName(name, &kind)) << name;
  }
  EXPECT_TRUE(IsPluginGaitOutputName("LKneeAngles", &kind));
  EXPECT_EQ(kind, "ANGLES");
  EXPECT_TRUE(IsPluginGaitOutputName("RGroundReactionForce", &kind));
  EXPECT_EQ(kind, "FORCES");
  // Marker names of the sets in the data (Vicon, CMU, Codamotion, c3d.org) are not outputs.
  for (const char* name : {"LASI", "RKNE", "LFHD", "PELV", "STRN", "CLAV", "L.Sac.Wand", "R.Hip", "pv4", "RFT1",
                           "*52", "Force", "XPower", "LTOE", "RHEE", "LFE", "sacrum", "r should"}) {
    EXPECT_FALSE(IsPluginGaitOutputName(name)) << name;
  }
}

TEST(C3dPoints, RoundTripKeepsTheModelOutputs) {
  MarkerTrajectories first, second;
  ASSERT_TRUE(Read(NexusFixture(), &first).ok());
  std::string bytes;
  Status status = EncodeC3d(first, "rewritten.c3d", &bytes);
  ASSERT_TRUE(status.ok()) << status.message();
  status = ParseC3d(bytes, "rewritten.c3d", &second);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(second.labels(), first.labels());
  EXPECT_EQ(second.subject_prefixes, first.subject_prefixes);
  for (int f = 0; f < first.num_frames(); ++f) {
    for (int m = 0; m < first.num_markers(); ++m) EXPECT_EQ(second.position(f, m), first.position(f, m));
  }
  ASSERT_NE(second.model_outputs, nullptr);
  const ModelOutputPoints& a = *first.model_outputs;
  const ModelOutputPoints& b = *second.model_outputs;
  EXPECT_EQ(b.points.labels(), a.points.labels());
  EXPECT_EQ(b.kinds, a.kinds);
  for (int f = 0; f < a.points.num_frames(); ++f) {
    for (int m = 0; m < a.points.num_markers(); ++m) {
      EXPECT_EQ(b.points.valid(f, m), a.points.valid(f, m));
      if (a.points.valid(f, m)) {
        EXPECT_EQ(b.points.position(f, m), a.points.position(f, m));
      }
    }
  }
  // Read back with --include_model_outputs: all 13 points, the outputs after the markers.
  C3dReadOptions options;
  options.include_model_outputs = true;
  MarkerTrajectories all;
  ASSERT_TRUE(ParseC3d(bytes, "rewritten.c3d", &all, nullptr, options).ok());
  EXPECT_EQ(all.num_markers(), 13);
  EXPECT_EQ(all.label(4), "Pat:LKneeAngles");
}

TEST(C3dPoints, ACutTakeIsWrittenWithoutItsModelOutputs) {
  MarkerTrajectories t;
  ASSERT_TRUE(Read(NexusFixture(), &t).ok());
  MarkerTrajectories cut(t.labels(), 2);
  cut.frame_rate = t.frame_rate;
  cut.model_outputs = t.model_outputs;  // 3 frames: no longer the take's.
  std::string bytes;
  ASSERT_TRUE(EncodeC3d(cut, "cut.c3d", &bytes).ok());
  MarkerTrajectories back;
  ASSERT_TRUE(ParseC3d(bytes, "cut.c3d", &back).ok());
  EXPECT_EQ(back.num_markers(), 4);
  EXPECT_EQ(back.model_outputs, nullptr);
}

// ---------------------------------------------------------------------------------------
// Subjects and props (two label prefixes in one file).

VendorC3d TwoSubjectFixture(bool with_subjects_group) {
  VendorC3d fixture;
  fixture.labels = {"Daphnee:LASI", "boite:M1", "Daphnee:RASI", "boite:M2", "", "Daphnee:LKneeAngles"};
  if (with_subjects_group) {
    fixture.strings = {{"SUBJECTS:NAMES", {"Daphnee", "boite"}},
                       {"SUBJECTS:LABEL_PREFIXES", {"Daphnee:", "boite:"}}};
  }
  return fixture;
}

// Without a choice, a file of several subjects is read as the one with the most points (an
// actor over a prop), or as the caller's preferred subject when the file has it; a warning
// lists the subjects and says which was read.
TEST(C3dPoints, SeveralSubjectsWithoutAChoiceReadTheLargestOrThePreferredOne) {
  for (bool with_group : {true, false}) {
    MarkerTrajectories t;
    C3dFileInfo info;
    ASSERT_TRUE(Read(TwoSubjectFixture(with_group), &t, &info, C3dReadOptions()).ok());
    EXPECT_EQ(t.labels(), (std::vector<std::string>{"LASI", "RASI", "*5"}));
    EXPECT_EQ(info.other_subject_points, 2);
    const std::string where = with_group ? "SUBJECTS:LABEL_PREFIXES" : "POINT:LABELS (subject prefixes)";
    const std::string warning = where + ": 2 subjects ('Daphnee:', 'boite:'); reading 'Daphnee:' (the one with "
                                "the most points); --subject_prefix=NAME reads another";
    EXPECT_EQ(std::count_if(info.warnings.begin(), info.warnings.end(),
                            [&](const std::string& w) { return w.find(warning) != std::string::npos; }),
              1);
    C3dReadOptions options;
    options.preferred_subject_prefix = "boite:";
    ASSERT_TRUE(Read(TwoSubjectFixture(with_group), &t, &info, options).ok());
    EXPECT_EQ(t.labels(), (std::vector<std::string>{"M1", "M2", "*5"}));
    options.preferred_subject_prefix = "Nobody:";  // Not in the file: the largest again.
    ASSERT_TRUE(Read(TwoSubjectFixture(with_group), &t, &info, options).ok());
    EXPECT_EQ(t.labels(), (std::vector<std::string>{"LASI", "RASI", "*5"}));
  }
}

TEST(C3dPoints, SubjectPrefixSelectsOneSubjectAndStripsItsPrefix) {
  for (const char* choice : {"Daphnee", "Daphnee:"}) {
    for (bool with_group : {true, false}) {
      MarkerTrajectories t;
      C3dFileInfo info;
      C3dReadOptions options;
      options.subject_prefix = choice;
      const Status status = Read(TwoSubjectFixture(with_group), &t, &info, options);
      ASSERT_TRUE(status.ok()) << status.message();
      EXPECT_EQ(t.labels(), (std::vector<std::string>{"LASI", "RASI", "*5"})) << choice;
      EXPECT_EQ(SourcePoint(t, 1), 2);
      EXPECT_TRUE(t.subject_prefixes.empty());
      EXPECT_EQ(info.other_subject_points, 2);
      ASSERT_NE(t.model_outputs, nullptr);
      EXPECT_EQ(t.model_outputs->points.labels(), std::vector<std::string>{"LKneeAngles"});
    }
  }
  MarkerTrajectories prop;
  C3dReadOptions options;
  options.subject_prefix = "boite";
  ASSERT_TRUE(Read(TwoSubjectFixture(true), &prop, nullptr, options).ok());
  EXPECT_EQ(prop.labels(), (std::vector<std::string>{"M1", "M2", "*5"}));
  EXPECT_EQ(SourcePoint(prop, 1), 3);
}

TEST(C3dPoints, SubjectPrefixThatIsNotInTheFileIsAnError) {
  MarkerTrajectories t;
  C3dReadOptions options;
  options.subject_prefix = "Nobody";
  ExpectOneLineError(Read(TwoSubjectFixture(true), &t, nullptr, options),
                     "SUBJECTS:LABEL_PREFIXES: no subject 'Nobody' (subjects: 'Daphnee:', 'boite:')");
  VendorC3d plain;
  plain.labels = {"LASI"};
  ExpectOneLineError(Read(plain, &t, nullptr, options), "the file has no subject prefixes");
}

TEST(C3dPoints, OneSubjectKeepsItsLabelsRawUnlessChosen) {
  VendorC3d fixture = NexusFixture();
  MarkerTrajectories t;
  C3dReadOptions options;
  options.subject_prefix = "Pat";
  ASSERT_TRUE(Read(fixture, &t, nullptr, options).ok());
  EXPECT_EQ(t.labels(), (std::vector<std::string>{"LASI", "RASI", "RKNE", "*13"}));
  EXPECT_EQ(t.model_outputs->points.num_markers(), 9);
}

// ---------------------------------------------------------------------------------------
// Labels with spaces and lower case (Qualisys QTM, BTS), > 255 points (LABELS2).

TEST(C3dPoints, LabelsKeepCaseAndInnerSpacesTrimmedAtTheEnds) {
  VendorC3d fixture;
  fixture.labels = {" r should ", "sacrum", "L Knee  lat"};
  MarkerTrajectories t;
  ASSERT_TRUE(Read(fixture, &t).ok());
  EXPECT_EQ(t.labels(), (std::vector<std::string>{"r should", "sacrum", "L Knee  lat"}));
  EXPECT_EQ(t.FindMarker("r should"), 0);
  EXPECT_EQ(t.FindMarker("R SHOULD"), -1);  // Matching is exact (README: label case).
}

TEST(C3dPoints, MoreThan255PointsWithDuplicatesAndOutputsInLabels2) {
  VendorC3d fixture;
  for (int m = 0; m < 300; ++m) fixture.labels.push_back("M" + std::to_string(m));
  fixture.labels[280] = "M3";           // A duplicate across LABELS and LABELS2.
  fixture.labels[290] = "RKneeAngles";  // A model output in LABELS2.
  fixture.labels[299] = "X299";
  fixture.strings = {{"POINT:ANGLES", {"RKneeAngles"}}, {"POINT:SCALARS", {"X299"}}};
  MarkerTrajectories t;
  C3dFileInfo info;
  const Status status = Read(fixture, &t, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(t.num_markers(), 298);
  EXPECT_EQ(t.label(280), "M3#2");
  EXPECT_EQ(SourcePoint(t, 280), 280);
  EXPECT_EQ(SourcePoint(t, 290), 291);
  EXPECT_EQ(t.model_outputs->points.labels(), (std::vector<std::string>{"RKneeAngles", "X299"}));
  EXPECT_EQ(info.warnings.size(), 2u);
  // Rewritten and read back: the markers and both outputs again.
  std::string bytes;
  ASSERT_TRUE(EncodeC3d(t, "big.c3d", &bytes).ok());
  MarkerTrajectories back;
  ASSERT_TRUE(ParseC3d(bytes, "big.c3d", &back).ok());
  EXPECT_EQ(back.labels(), t.labels());
  EXPECT_EQ(back.model_outputs->kinds, (std::vector<std::string>{"ANGLES", "SCALARS"}));
}

// ---------------------------------------------------------------------------------------
// ReadMarkerFile and the CLI (the default options, warnings on stderr).

TEST(C3dPoints, ReadMarkerFileCollectsWarningsAndAppliesOptions) {
  const std::string path = TempPath("nexus.c3d");
  WriteTextFile(path, NexusFixture().Build());
  MarkerTrajectories t;
  std::vector<std::string> warnings;
  MarkerReadOptions options;
  options.warnings = &warnings;
  ASSERT_TRUE(ReadMarkerFile(path, &t, options).ok());
  EXPECT_EQ(t.num_markers(), 4);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].rfind(path + ": 9 of 13", 0), 0u) << warnings[0];
  options.include_model_outputs = true;
  ASSERT_TRUE(ReadMarkerFile(path, &t, options).ok());
  EXPECT_EQ(t.num_markers(), 13);
}

TEST(C3dPoints, CliReadsAndRewritesVendorFiles) {
  const std::string nexus = TempPath("nexus.c3d"), two = TempPath("two.c3d"), out = TempPath("out.c3d");
  WriteTextFile(nexus, NexusFixture().Build());
  WriteTextFile(two, TwoSubjectFixture(true).Build());
  std::string output;
  EXPECT_EQ(RunCli("info " + nexus, &output), 0) << output;
  EXPECT_NE(output.find("9 of 13 points are model outputs"), std::string::npos) << output;
  EXPECT_EQ(RunCli("convert " + nexus + " " + out, &output), 0) << output;
  MarkerTrajectories back;
  ASSERT_TRUE(ReadC3d(out, &back).ok());
  EXPECT_EQ(back.num_markers(), 4);
  ASSERT_NE(back.model_outputs, nullptr);
  EXPECT_EQ(back.model_outputs->points.num_markers(), 9);
  EXPECT_EQ(RunCli("info --include_model_outputs " + nexus, &output), 0) << output;
  EXPECT_EQ(output.find("model outputs"), std::string::npos) << output;

  EXPECT_EQ(RunCli("info " + two, &output), 0) << output;
  EXPECT_NE(output.find("2 subjects ('Daphnee:', 'boite:'); reading 'Daphnee:'"), std::string::npos) << output;
  EXPECT_NE(output.find("markers:   3 (LASI, RASI, *5)"), std::string::npos) << output;
  EXPECT_EQ(RunCli("info --subject_prefix=boite " + two, &output), 0) << output;
  EXPECT_NE(output.find("markers:   3 (M1, M2, *5)"), std::string::npos) << output;
  // Commands that read no marker file do not take the flags.
  EXPECT_EQ(RunCli("fk --subject_prefix=boite --motion=x.bvh --out=y.bvh", &output), 1) << output;
  EXPECT_NE(output.find("--subject_prefix: not a flag of `fk`"), std::string::npos) << output;
}

}  // namespace
}  // namespace mocapsolve
