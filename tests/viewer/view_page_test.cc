// The page's data: base64, the int16 position quantization, the template filling; the
// scene's transforms and up-axis guess; repair intervals and their reasons.
#include "viewer/view_page.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/csv_columns.h"
#include "io/gzip.h"
#include "io/json_reader.h"
#include "tests/test_support.h"
#include "viewer/repair_intervals.h"
#include "viewer/view_scene.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

std::string Unbase64(const std::string& text) {
  static const std::string kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  int bits = 0, value = 0;
  for (char c : text) {
    if (c == '=') break;
    value = (value << 6) | static_cast<int>(kAlphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((value >> bits) & 0xff);
    }
  }
  return out;
}

// A page's array: base64 of a gzip stream.
std::string Inflated(const std::string& base64) {
  std::string bytes;
  const Status status = GzipDecompress(Unbase64(base64), &bytes);
  EXPECT_TRUE(status.ok()) << status.message();
  return bytes;
}

std::string Between(const std::string& text, const std::string& open, const std::string& close) {
  const size_t a = text.find(open);
  if (a == std::string::npos) return "";
  const size_t b = text.find(close, a + open.size());
  return text.substr(a + open.size(), b - a - open.size());
}

TEST(ViewPage, Base64MatchesRfc4648) {
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foo"), "Zm9v");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(Unbase64(Base64(std::string("\0\xff\x10", 3))), std::string("\0\xff\x10", 3));
}

TEST(ViewPage, EmbedsQuantizedPositionsStatesAndEscapedText) {
  ViewScene scene;
  scene.title = "a </script> <b>";
  scene.frame_rate = 60;
  ViewMarkers markers;
  markers.name = "m";
  markers.labels = {"A", "</script>"};
  markers.num_frames = 2;
  markers.positions = {0.0f, 1.0f, -2.0f, 3.5f, 1.5f, 0.25f, std::nanf(""), 0.f, 0.f, 1.0f, 1.0f, 1.0f};
  markers.states = {0, 0, 1, 2};
  scene.markers.push_back(markers);
  std::string html;
  ASSERT_TRUE(BuildViewPage(scene, "/*runtime*/ var MOCAPSOLVE_THREE = {};", &html).ok());
  EXPECT_THAT(html, HasSubstr("<title>a &lt;/script&gt; &lt;b&gt;</title>"));
  EXPECT_THAT(html, HasSubstr("/*runtime*/"));
  EXPECT_THAT(html, HasSubstr("window.mocapsolveView"));
  EXPECT_THAT(html, HasSubstr("\"\\u003c/script>\""));  // The label cannot end the JSON's element.
  EXPECT_EQ(html.find("@DATA@"), std::string::npos);
  // Positions: int16 per axis around the box's centre, steps <= extent / 65534; NaN ->
  // -32768; gzip-compressed, each frame stored as its difference from the previous one.
  EXPECT_THAT(html, HasSubstr("\"compression\": \"gzip\", \"delta\": 6,"));
  const std::string bytes = Inflated(Between(html, "id=\"mv-blob-0\">", "</script>"));
  ASSERT_EQ(bytes.size(), 12 * sizeof(std::int16_t));
  std::vector<std::int16_t> q(12);
  std::memcpy(q.data(), bytes.data(), bytes.size());
  for (size_t i = 6; i < q.size(); ++i) q[i] = static_cast<std::int16_t>(q[i] + q[i - 6]);  // Wrapping, as the page.
  EXPECT_EQ(q[6], -32768);
  const double step_x = 3.5 / 65534.0, origin_x = 1.75;
  EXPECT_NEAR(origin_x + step_x * q[0], 0.0, step_x);
  EXPECT_NEAR(origin_x + step_x * q[3], 3.5, step_x);
  EXPECT_EQ(Inflated(Between(html, "id=\"mv-blob-1\">", "</script>")), std::string("\0\0\1\2", 4));
}

// Text from files inside the page's JSON element: whatever a label or title holds, the
// element ends at our own "</script>", holds no '<' at all (so neither "</script" nor
// "<!--" with "<script", which would switch the HTML parser into the double-escaped state and
// swallow the rest of the page), and parses back to the very same strings.
TEST(ViewPage, ScriptDataCannotEndOrSwallowTheDataElement) {
  const std::vector<std::string> hostile = {"<!--<script>", "</script>", "</SCRIPT ", "<!--", "-->", "<script>",
                                            "a<b>&amp;\"q\"", "\x1b[31mred"};
  ViewScene scene;
  scene.title = "<!--<script>title";
  scene.frame_rate = 30;
  ViewMarkers markers;
  markers.name = "<!--<script>";
  markers.labels = hostile;
  markers.num_frames = 1;
  markers.positions.assign(3 * hostile.size(), 1.0f);
  markers.states.assign(hostile.size(), 0);
  scene.markers.push_back(markers);
  std::string html;
  ASSERT_TRUE(BuildViewPage(scene, "/*runtime*/", &html).ok());
  const std::string data = Between(html, "id=\"mv-meta\">", "</script>");
  EXPECT_EQ(data.find('<'), std::string::npos) << data;
  JsonNode meta;
  ASSERT_TRUE(ParseJson(data, "mv-meta", &meta).ok());
  ASSERT_NE(meta.Find("title"), nullptr);
  EXPECT_EQ(meta.Find("title")->string, scene.title);
  const JsonNode* parsed = meta.Find("markers");
  ASSERT_TRUE(parsed != nullptr && parsed->is_array() && parsed->items.size() == 1);
  const JsonNode* labels = parsed->items[0].Find("labels");
  ASSERT_TRUE(labels != nullptr && labels->items.size() == hostile.size());
  for (size_t i = 0; i < hostile.size(); ++i) EXPECT_EQ(labels->items[i].string, hostile[i]);
  // The element that follows the data is still there: the page was not swallowed.
  EXPECT_THAT(html.substr(html.find("id=\"mv-meta\">")), HasSubstr("id=\"mv-blob-0\">"));
}

TEST(ViewPage, RefusesAnEmptySceneAndABadRate) {
  ViewScene scene;
  std::string html;
  EXPECT_THAT(BuildViewPage(scene, "", &html).message(), HasSubstr("nothing to show"));
  scene.frame_rate = 0;
  EXPECT_THAT(BuildViewPage(scene, "", &html).message(), HasSubstr("frame rate"));
}

TEST(ViewScene, ZUpBecomesYUpAndUnitsBecomeMetres) {
  ViewTransform t;
  ASSERT_TRUE(MakeViewTransform("m.c3d", 2, Millimetres(), 0.0, &t).ok());
  const Eigen::Vector3d head = t.Apply(Eigen::Vector3d(100, 200, 1700));
  EXPECT_TRUE(head.isApprox(Eigen::Vector3d(0.1, 1.7, -0.2)));
  EXPECT_NEAR(t.rotation.determinant(), 1.0, 1e-12);
  EXPECT_THAT(t.note, HasSubstr("mm, +z up"));
  // Unknown unit: guessed from the height when one is plausible, else an error.
  ASSERT_TRUE(MakeViewTransform("x.bvh", 1, LengthUnit(), 170.0, &t).ok());
  EXPECT_DOUBLE_EQ(t.scale, 0.01);
  EXPECT_THAT(t.note, HasSubstr("guessed"));
  EXPECT_FALSE(MakeViewTransform("x.bvh", 1, LengthUnit(), 0.0, &t).ok());
}

TEST(ViewScene, GuessesTheAxisAPersonIsTallAlong) {
  std::vector<std::vector<Eigen::Vector3d>> frames(10);
  for (int f = 0; f < 10; ++f) {
    // A walker along x over the take (each frame 0.4 wide in x, 1.7 tall in z).
    frames[f] = {{0.3 * f, 0.0, 0.0}, {0.3 * f + 0.4, 0.2, 1.7}, {0.3 * f, std::nan(""), 0.5}};
  }
  EXPECT_EQ(GuessUpAxis(frames), 2);
  EXPECT_EQ(GuessUpAxis({}), 1);
}

TEST(RepairIntervals, FilledIntervalsTakeTheDetectedReason) {
  const std::vector<ReportedInterval> detected = {{0, 10, 20, "outlier"}, {0, 21, 22, "missing"},
                                                  {1, 5, 9, "joint difference"}};
  const std::vector<ReportedInterval> filled = {{0, 9, 22, "reference"}, {1, 5, 9, "polynomial"},
                                                {2, 1, 3, "reference"}};
  const std::vector<ViewInterval> intervals = RepairedViewIntervals(detected, filled);
  ASSERT_EQ(intervals.size(), 3u);
  EXPECT_EQ(intervals[0].state, MarkerState::kRepairedOutlier);  // Overlaps most.
  EXPECT_EQ(intervals[1].state, MarkerState::kRepairedJointDifference);
  EXPECT_EQ(intervals[2].state, MarkerState::kRepairedGap);
  ViewMarkers markers;
  markers.labels = {"A", "B", "C"};
  markers.num_frames = 12;
  markers.states.assign(36, 0);
  MarkRepairedSamples(intervals, &markers);
  EXPECT_EQ(markers.states[11 * 3 + 0], static_cast<std::uint8_t>(MarkerState::kRepairedOutlier));  // Clipped at 11.
  EXPECT_EQ(markers.states[4 * 3 + 1], 0);
  EXPECT_EQ(markers.states[5 * 3 + 1], static_cast<std::uint8_t>(MarkerState::kRepairedJointDifference));
}

// Unlabelled points a repair assigned are drawn as their own state (they are observations,
// not fills) and are no fill's reason.
TEST(RepairIntervals, AssignedUnlabelledPointsHaveTheirOwnState) {
  const std::vector<ReportedInterval> detected = {{0, 10, 20, "unlabelled"}, {0, 5, 30, "missing"}};
  const std::vector<ReportedInterval> filled = {{0, 21, 30, "reference"}};
  const std::vector<ViewInterval> intervals = RepairedViewIntervals(detected, filled);
  ASSERT_EQ(intervals.size(), 2u);
  EXPECT_EQ(intervals[0].state, MarkerState::kRepairedUnlabelled);
  EXPECT_EQ(intervals[0].first, 10);
  EXPECT_EQ(intervals[1].state, MarkerState::kRepairedGap);
  EXPECT_STREQ(MarkerStateName(MarkerState::kRepairedUnlabelled), "unlabelled");
  EXPECT_EQ(RepairedStateForReason("unlabelled"), MarkerState::kRepairedUnlabelled);
}

TEST(RepairIntervals, ReportErrorsNameTheFieldAndPrefixedLabelsMatch) {
  const std::string path = testing::TempPath("r.json");
  auto write = [&](const std::string& text) {
    FILE* f = std::fopen(path.c_str(), "w");
    std::fputs(text.c_str(), f);
    std::fclose(f);
  };
  const std::vector<std::string> labels = {"Subject:LKNE", "RKNE"};
  std::vector<ReportedInterval> detected, filled;
  write("{\"detected\": [{\"marker\": \"LKNE\", \"first_frame\": 2, \"last_frame\": 4, \"what\": \"outlier\"}],"
        " \"filled\": []}");
  ASSERT_TRUE(ReadRepairReport(path, labels, 10, &detected, &filled).ok());
  ASSERT_EQ(detected.size(), 1u);
  EXPECT_EQ(detected[0].marker, 0);
  write("{\"detected\": [], \"filled\": [{\"marker\": \"RKNE\", \"first_frame\": 2, \"last_frame\": 10}]}");
  EXPECT_THAT(ReadRepairReport(path, labels, 10, &detected, &filled).message(), HasSubstr("filled[0]"));
  write("{\"filled\": []}");
  EXPECT_THAT(ReadRepairReport(path, labels, 10, &detected, &filled).message(), HasSubstr("detected"));
}

TEST(CsvColumns, ReadsColumnsAndNamesBadRows) {
  const std::string path = testing::TempPath("w.csv");
  FILE* f = std::fopen(path.c_str(), "w");
  std::fputs("frame,weight\n0,0.5\n1,1\n\n2,0.25\n", f);
  std::fclose(f);
  CsvColumns table;
  ASSERT_TRUE(ReadCsvColumns(path, &table).ok());
  EXPECT_EQ(table.names, (std::vector<std::string>{"frame", "weight"}));
  EXPECT_EQ(table.columns[1], (std::vector<double>{0.5, 1.0, 0.25}));
  f = std::fopen(path.c_str(), "w");
  std::fputs("frame,weight\n0,0.5\n1,x\n", f);
  std::fclose(f);
  EXPECT_THAT(ReadCsvColumns(path, &table).message(), HasSubstr("w.csv:3: weight: 'x'"));
}

}  // namespace
}  // namespace mocapsolve
