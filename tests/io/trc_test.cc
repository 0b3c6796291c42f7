#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/c3d_reader.h"
#include "io/marker_file.h"
#include "io/trc_reader.h"
#include "io/trc_writer.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

void ExpectOneLineError(const Status& status, const std::string& prefix, const std::string& part) {
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
  EXPECT_EQ(status.message().rfind(prefix, 0), 0u) << status.message();
  EXPECT_NE(status.message().find(part), std::string::npos)
      << "expected '" << part << "' in: " << status.message();
}

// A small valid file: 2 markers, 3 frames, RASI missing in frame 2 (empty cells) and
// LASI zero in frame 3.
const char kSmall[] =
    "PathFileType\t4\t(X/Y/Z)\tsmall.trc\n"
    "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames\n"
    "100\t100\t3\t2\tmm\t100\t5\t3\n"
    "Frame#\tTime\tLASI\t\t\tRASI\t\t\n"
    "\t\tX1\tY1\tZ1\tX2\tY2\tZ2\n"
    "\n"
    "5\t0.04\t100.5\t200\t900\t-100\t200\t900\n"
    "6\t0.05\t101\t200\t900\t\t\t\n"
    "7\t0.06\t0\t0\t0\t-98\t200\t9e2\t\n";

std::string WithLine(const std::string& text, int line, const std::string& replacement) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  lines[line - 1] = replacement;
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

TEST(TrcReader, SmallFileWithGaps) {
  MarkerTrajectories t;
  const Status status = ParseTrc(kSmall, "small.trc", &t);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(t.num_markers(), 2);
  EXPECT_EQ(t.num_frames(), 3);
  EXPECT_EQ(t.frame_rate, 100.0);
  EXPECT_EQ(t.unit.name, "mm");
  EXPECT_EQ(t.first_frame, 5);
  EXPECT_EQ(t.labels(), (std::vector<std::string>{"LASI", "RASI"}));
  EXPECT_EQ(t.position(0, 0), Eigen::Vector3d(100.5, 200, 900));
  EXPECT_EQ(t.position(2, 1), Eigen::Vector3d(-98, 200, 900));
  EXPECT_FALSE(t.valid(1, 1));  // Empty cells.
  EXPECT_FALSE(t.valid(2, 0));  // All zero.
  EXPECT_TRUE(t.position(2, 0).array().isNaN().all());
  EXPECT_EQ(t.CountMissing(), 2);

  TrcReadOptions keep_zeros;
  keep_zeros.zero_position_is_missing = false;
  ASSERT_TRUE(ParseTrc(kSmall, "small.trc", &t, keep_zeros).ok());
  EXPECT_TRUE(t.valid(2, 0));
  EXPECT_EQ(t.position(2, 0), Eigen::Vector3d::Zero());
}

TEST(TrcReader, CrLfAndNanCells) {
  std::string text = WithLine(kSmall, 8, "6\t0.05\t101\t200\t900\tNaN\tnan\tnan");
  std::string crlf;
  for (char c : text) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  MarkerTrajectories t;
  const Status status = ParseTrc(crlf, "crlf.trc", &t);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_FALSE(t.valid(1, 1));
  EXPECT_EQ(t.label(1), "RASI");
  EXPECT_EQ(t.position(0, 0), Eigen::Vector3d(100.5, 200, 900));
}

// ---------------------------------------------------------------------------------------
// (d) The data set's TRC files.

TEST(TrcReader, Subject01Walk) {
  MOCAPSOLVE_DATA_FILE(path, "trc/subject01_walk1.trc");
  MarkerTrajectories t;
  const Status status = ReadTrc(path, &t);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(t.num_markers(), 41);
  EXPECT_EQ(t.num_frames(), 151);
  EXPECT_EQ(t.frame_rate, 60.0);
  EXPECT_EQ(t.unit.name, "mm");
  EXPECT_EQ(t.first_frame, 1);
  EXPECT_EQ(t.CountMissing(), 0);
  EXPECT_EQ(t.label(0), "R.ASIS");
  EXPECT_EQ(t.label(40), "Top.Head");
  EXPECT_EQ(t.position(0, 0), Eigen::Vector3d(617.247620, 1055.275020, 170.781980));
  // Y-up: the head is the highest marker, in 33-1809 mm.
  double min_y = 1e9, max_y = -1e9;
  for (Eigen::Index i = 0; i < t.positions().cols(); ++i) {
    min_y = std::min(min_y, t.positions()(1, i));
    max_y = std::max(max_y, t.positions()(1, i));
  }
  EXPECT_GT(min_y, 30.0);
  EXPECT_LT(max_y, 1810.0);
}

TEST(TrcReader, Subject02RunningHasAnAllZeroMarker) {
  MOCAPSOLVE_DATA_FILE(path, "trc/subject02_running.trc");
  MarkerTrajectories t;
  const Status status = ReadTrc(path, &t);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(t.num_markers(), 41);
  EXPECT_EQ(t.num_frames(), 600);
  EXPECT_EQ(t.unit.name, "mm");
  const int bicep = t.FindMarker("L.Bicep");
  ASSERT_GE(bicep, 0);
  EXPECT_EQ(t.CountMissing(bicep), 600);
  EXPECT_EQ(t.CountMissing(), 600);  // Nothing else is missing.
}

TEST(TrcReader, JA1Gait35InMetresWithNanCells) {
  MOCAPSOLVE_DATA_FILE(path, "trc/JA1Gait35.trc");
  MarkerTrajectories t;
  const Status status = ReadTrc(path, &t);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(t.num_markers(), 53);
  EXPECT_EQ(t.num_frames(), 322);
  EXPECT_EQ(t.frame_rate, 250.0);
  EXPECT_EQ(t.unit.name, "m");
  EXPECT_EQ(t.unit.metres_per_unit, 1.0);
  // The data README says "no missing samples", but 46 samples are literal "nan" cells
  // (LARM 9, LELB 6, RMFS 5, ...): AddBiomechanics' outlier removal.
  EXPECT_EQ(t.CountMissing(), 46);
  EXPECT_EQ(t.CountMissing(t.FindMarker("LARM")), 9);
}

TEST(TrcReader, JA1Gait35AgreesWithItsC3d) {
  // What the comparison found: TRC = (y, z, x) of the C3D / 1000 (Z-up mm -> Y-up m, a
  // cyclic axis permutation, no translation), and TRC frame f = C3D frame f + 2 (the
  // TRC drops the C3D's first two frames, fields 833-834). Where both have a sample,
  // 99.9 % agree within 7 micrometres (the TRC's 6 significant digits); 12 samples next
  // to the TRC's removed outliers differ by up to 23 cm, and 45 samples valid in the
  // C3D are nan in the TRC. So: the same data, unfiltered, with a few spikes removed.
  MOCAPSOLVE_DATA_FILE(trc_path, "trc/JA1Gait35.trc");
  MOCAPSOLVE_DATA_FILE(c3d_path, "c3d/JA1Gait35.c3d");
  MarkerTrajectories trc, c3d;
  ASSERT_TRUE(ReadTrc(trc_path, &trc).ok());
  ASSERT_TRUE(ReadC3d(c3d_path, &c3d).ok());
  ASSERT_TRUE(ConvertUnits(Metres(), &c3d).ok());
  ASSERT_EQ(c3d.num_frames(), trc.num_frames() + 2);
  constexpr int kFrameOffset = 2;
  int compared = 0, close = 0, trc_only = 0, c3d_only = 0;
  std::vector<double> differences;
  for (int m = 0; m < trc.num_markers(); ++m) {
    // Unlabelled points: "*52" in the C3D, "x52" in the TRC.
    int c = c3d.FindMarker(trc.label(m));
    if (c < 0 && trc.label(m)[0] == 'x') c = c3d.FindMarker("*" + trc.label(m).substr(1));
    ASSERT_GE(c, 0) << trc.label(m);
    for (int f = 0; f < trc.num_frames(); ++f) {
      const bool in_trc = trc.valid(f, m), in_c3d = c3d.valid(f + kFrameOffset, c);
      trc_only += in_trc && !in_c3d;
      c3d_only += in_c3d && !in_trc;
      if (!in_trc || !in_c3d) continue;
      const Eigen::Vector3d z_up = c3d.position(f + kFrameOffset, c);
      const Eigen::Vector3d y_up(z_up.y(), z_up.z(), z_up.x());
      const double difference = (y_up - trc.position(f, m)).norm();
      differences.push_back(difference);
      ++compared;
      close += difference < 1e-5;  // 10 micrometres.
    }
  }
  std::sort(differences.begin(), differences.end());
  std::printf("JA1Gait35 TRC vs C3D: %d samples compared, median %.2g m, %d within 10 um, "
              "max %.3f m; %d only in the TRC, %d only in the C3D\n",
              compared, differences[differences.size() / 2], close, differences.back(),
              trc_only, c3d_only);
  EXPECT_EQ(compared, 17020);
  EXPECT_EQ(trc_only, 0);
  EXPECT_EQ(c3d_only, 45);
  EXPECT_LT(differences[differences.size() / 2], 5e-6);
  EXPECT_GE(close, compared - 12);
}

// ---------------------------------------------------------------------------------------
// Writer round trips.

TEST(TrcWriter, RoundTripKeepsValuesAndGaps) {
  MarkerTrajectories written(std::vector<std::string>{"Sub:LASI", "R.ASIS", "C7"}, 4);
  written.frame_rate = 120.0;
  written.unit = Millimetres();
  written.first_frame = 50;
  written.SetSample(0, 0, Eigen::Vector3d(1.0 / 3.0, -2e-7, 1234.5678901234));
  written.SetSample(1, 1, Eigen::Vector3d(617.2476196289062, 1.5, -3));  // A float value.
  written.SetSample(3, 2, Eigen::Vector3d(1e6, -1e-3, 0.1));
  std::string text;
  Status status = FormatTrc(written, "out/round.trc", &text);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(text.rfind("PathFileType\t4\t(X/Y/Z)\tround.trc\n", 0), 0u) << text;
  EXPECT_NE(text.find("617.2476\t"), std::string::npos) << text;  // Shortest float text.
  MarkerTrajectories read;
  status = ParseTrc(text, "round.trc", &read);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(read.labels(), written.labels());
  EXPECT_EQ(read.frame_rate, 120.0);
  EXPECT_EQ(read.first_frame, 50);
  EXPECT_EQ(read.unit.name, "mm");
  EXPECT_EQ(read.valid_mask(), written.valid_mask());
  EXPECT_EQ(read.position(0, 0), written.position(0, 0));  // Doubles: exact.
  EXPECT_EQ(read.position(3, 2), written.position(3, 2));
  EXPECT_EQ(read.position(1, 1).cast<float>(), written.position(1, 1).cast<float>());
  EXPECT_EQ(read.FindMarker("LASI"), 0);
}

TEST(TrcWriter, RealFilesRoundTrip) {
  for (const char* file : {"trc/subject01_walk1.trc", "trc/subject02_running.trc",
                           "trc/JA1Gait35.trc"}) {
    MOCAPSOLVE_DATA_FILE(path, file);
    MarkerTrajectories original, read;
    ASSERT_TRUE(ReadTrc(path, &original).ok());
    const std::string copy = mocapsolve::testing::TempPath("copy.trc");
    Status status = WriteTrc(copy, original);
    ASSERT_TRUE(status.ok()) << status.message();
    status = ReadTrc(copy, &read);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(read.labels(), original.labels());
    EXPECT_EQ(read.valid_mask(), original.valid_mask()) << file;
    for (Eigen::Index i = 0; i < read.positions().cols(); ++i) {
      if (!original.valid_mask()[i]) continue;
      // Values parsed from decimal text are doubles: written shortest, read back exactly.
      ASSERT_EQ(read.positions().col(i), original.positions().col(i)) << file << " " << i;
    }
  }
}

TEST(TrcWriter, C3dToTrcKeepsFloatValues) {
  MOCAPSOLVE_DATA_FILE(path, "c3d/nick_freeform_001.c3d");
  MarkerTrajectories c3d, read;
  ASSERT_TRUE(ReadC3d(path, &c3d).ok());
  std::string text;
  ASSERT_TRUE(FormatTrc(c3d, "nick.trc", &text).ok());
  const Status status = ParseTrc(text, "nick.trc", &read);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(read.valid_mask(), c3d.valid_mask());
  EXPECT_EQ(read.CountMissing(), 3874);
  EXPECT_EQ(read.FindMarker("CLAV"), c3d.FindMarker("CLAV"));  // Prefix via the ':' rule.
  for (Eigen::Index i = 0; i < read.positions().cols(); ++i) {
    if (!c3d.valid_mask()[i]) continue;
    ASSERT_EQ(read.positions().col(i).cast<float>(), c3d.positions().col(i).cast<float>());
  }
}

TEST(TrcWriter, RejectsWhatTrcCannotHold) {
  std::string text;
  MarkerTrajectories t(std::vector<std::string>{"A"}, 1);
  t.frame_rate = 100.0;
  ExpectOneLineError(FormatTrc(t, "out.trc", &text), "out.trc: ", "unknown");
  t.unit = Metres();
  t.set_label(0, "has\ttab");
  ExpectOneLineError(FormatTrc(t, "out.trc", &text), "out.trc: ", "tab");
  t.set_label(0, "");
  ExpectOneLineError(FormatTrc(t, "out.trc", &text), "out.trc: ", "empty");
}

// ---------------------------------------------------------------------------------------
// (e) Bad input: one line naming the file and line.

MarkerTrajectories g_sink;

Status ParseBad(const std::string& text) { return ParseTrc(text, "bad.trc", &g_sink); }

TEST(TrcBadInput, TooFewColumns) {
  ExpectOneLineError(ParseBad(WithLine(kSmall, 8, "6\t0.05\t101\t200\t900\t1\t2")), "bad.trc:8: ",
                     "7 columns, expected 2 + 3 x 2 = 8");
}

TEST(TrcBadInput, NonNumericCell) {
  ExpectOneLineError(ParseBad(WithLine(kSmall, 7, "5\t0.04\t100.5\tabc\t900\t-100\t200\t900")),
                     "bad.trc:7: ", "column 4 (Y of 'LASI') 'abc'");
  ExpectOneLineError(ParseBad(WithLine(kSmall, 7, "5\t0.04\t100.5\t1.5x\t900\t-100\t200\t900")),
                     "bad.trc:7: ", "'1.5x'");
  ExpectOneLineError(ParseBad(WithLine(kSmall, 7, "five\t0.04\t1\t2\t3\t4\t5\t6")), "bad.trc:7: ",
                     "Frame#");
  ExpectOneLineError(ParseBad(WithLine(kSmall, 7, "5\t\t1\t2\t3\t4\t5\t6")), "bad.trc:7: ", "Time");
}

TEST(TrcBadInput, ExtraNonEmptyColumns) {
  ExpectOneLineError(ParseBad(WithLine(kSmall, 7, "5\t0.04\t1\t2\t3\t4\t5\t6\t7")), "bad.trc:7: ",
                     "column 9");
}

TEST(TrcBadInput, FrameCountDisagrees) {
  ExpectOneLineError(ParseBad(WithLine(kSmall, 3, "100\t100\t4\t2\tmm\t100\t5\t4")), "bad.trc:",
                     "3 frame rows, but NumFrames is 4");
  ExpectOneLineError(ParseBad(WithLine(kSmall, 3, "100\t100\t99999999999\t2\tmm\t100\t5\t4")),
                     "bad.trc:3: ", "NumFrames");
}

TEST(TrcBadInput, MarkerCountDisagrees) {
  ExpectOneLineError(ParseBad(WithLine(kSmall, 3, "100\t100\t3\t3\tmm\t100\t5\t3")), "bad.trc:4: ",
                     "2 marker names, but NumMarkers is 3");
}

TEST(TrcBadInput, BadHeaderValues) {
  ExpectOneLineError(ParseBad(WithLine(kSmall, 3, "100\t100\t3\t2\tfurlongs\t100\t5\t3")),
                     "bad.trc:3: ", "Units 'furlongs'");
  ExpectOneLineError(ParseBad(WithLine(kSmall, 3, "0\t100\t3\t2\tmm\t100\t5\t3")), "bad.trc:3: ",
                     "DataRate");
  ExpectOneLineError(ParseBad(WithLine(kSmall, 3, "100\t100\t3")), "bad.trc:3: ", "missing NumMarkers");
  ExpectOneLineError(ParseBad(WithLine(kSmall, 1, "HELLO")), "bad.trc:1: ", "PathFileType");
  ExpectOneLineError(ParseBad(WithLine(kSmall, 4, "Time\tFrame#")), "bad.trc:4: ", "Frame#");
}

TEST(TrcBadInput, Truncated) {
  ExpectOneLineError(ParseBad(std::string(kSmall).substr(0, 60)), "bad.trc:", "5-line TRC header");
  ExpectOneLineError(ParseBad(""), "bad.trc:", "5-line TRC header");
  // Cut inside the last row: too few columns on that line.
  const std::string text(kSmall);
  ExpectOneLineError(ParseBad(text.substr(0, text.size() - 8)), "bad.trc:9: ", "columns");
}

TEST(TrcBadInput, BinaryGarbageIsAnErrorNotACrash) {
  std::string garbage;
  for (int i = 0; i < 4096; ++i) garbage += static_cast<char>((i * 131 + 7) % 256);
  EXPECT_FALSE(ParseBad(garbage).ok());
  EXPECT_FALSE(ParseBad(std::string(kSmall) + garbage).ok());
}

TEST(TrcBadFiles, HandmadeBadFilesFailWithOneLine) {
  for (const char* name : {"bad_columns.trc", "bad_number.trc"}) {
    const std::string path = mocapsolve::testing::SourcePath(std::string("tests/data/bad/") + name);
    MarkerTrajectories t;
    const Status status = ReadTrc(path, &t);
    ASSERT_FALSE(status.ok()) << name;
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
    EXPECT_NE(status.message().find(std::string(name) + ":8: "), std::string::npos)
        << status.message();
    std::printf("%s\n", status.message().c_str());
  }
}

// Two actors' prefixed labels in one TRC (as Cortex and Nexus export them): read as one
// actor, chosen as a C3D's subjects are, the other actor's columns dropped.
TEST(TrcReader, TwoActorsAreReadAsOne) {
  const std::string path = mocapsolve::testing::TempPath("two_actors.trc");
  mocapsolve::testing::WriteTextFile(
      path,
      "PathFileType\t4\t(X/Y/Z)\ttwo_actors.trc\n"
      "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\n"
      "100\t100\t2\t3\tmm\n"
      "Frame#\tTime\tAnn:LASI\t\t\tBob:LASI\t\t\tAnn:RASI\t\t\n"
      "\t\tX1\tY1\tZ1\tX2\tY2\tZ2\tX3\tY3\tZ3\n"
      "1\t0\t1\t2\t3\t10\t20\t30\t4\t5\t6\n"
      "2\t0.01\t1\t2\t3\t10\t20\t30\t\t\t\n");
  MarkerReadOptions options;
  std::vector<std::string> warnings;
  options.warnings = &warnings;
  MarkerTrajectories t;
  ASSERT_TRUE(ReadMarkerFile(path, &t, options).ok());
  EXPECT_EQ(t.labels(), (std::vector<std::string>{"LASI", "RASI"}));  // Ann has the most points.
  EXPECT_EQ(t.position(0, 1), Eigen::Vector3d(4, 5, 6));
  EXPECT_FALSE(t.valid(1, 1));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("2 subjects ('Ann:', 'Bob:'); reading 'Ann:'"), std::string::npos) << warnings[0];

  options.preferred_subject_prefix = "Bob:";  // A subject file's own actor.
  ASSERT_TRUE(ReadMarkerFile(path, &t, options).ok());
  EXPECT_EQ(t.labels(), std::vector<std::string>{"LASI"});
  EXPECT_EQ(t.position(1, 0), Eigen::Vector3d(10, 20, 30));

  options.subject_prefix = "Carl";
  const Status status = ReadMarkerFile(path, &t, options);
  ExpectOneLineError(status, path + ": marker labels (subject prefixes): no subject 'Carl'", "'Ann:', 'Bob:'");
}

}  // namespace
}  // namespace mocapsolve
