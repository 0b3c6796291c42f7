// Batch summaries (batch/batch_summary.h): hostile take names give inert links in
// summary.html, gate_failed is its own status, and a summary written while the batch runs
// lists the ended takes and counts the others as pending. The JSON is written last, so a
// batch killed between the three writes never leaves a summary.json without its pages.
#include "batch/batch_summary.h"

#include <sys/stat.h>

#include <algorithm>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TakeOutcome Ended(const std::string& take, const std::string& status, const std::string& view = "view.html") {
  TakeOutcome outcome;
  outcome.ran = true;
  outcome.record.take = take;
  outcome.record.status = status;
  outcome.record.exit = status == "done" ? "0" : status == "gate_failed" ? "3" : "1";
  outcome.record.figures.view = view;
  return outcome;
}

// Every href of the page.
std::vector<std::string> Hrefs(const std::string& html) {
  std::vector<std::string> hrefs;
  for (size_t at = html.find("href=\""); at != std::string::npos; at = html.find("href=\"", at + 1)) {
    const size_t begin = at + 6;
    hrefs.push_back(html.substr(begin, html.find('"', begin) - begin));
  }
  return hrefs;
}

TEST(BatchSummaryHtml, HostileTakeNamesGiveRelativeInertLinks) {
  const std::vector<std::string> names = {"javascript:alert(1)", "\"><script>alert(1)</script>", "a b#c?d%e",
                                          "caf\xc3\xa9", "data:text/html,x", "'onmouseover='x"};
  BatchResult result;
  for (const std::string& name : names) result.takes.push_back(Ended(name, "done"));
  result.done = static_cast<int>(names.size());
  const std::string html = FormatSummaryHtml(result);
  const std::vector<std::string> hrefs = Hrefs(html);
  ASSERT_EQ(hrefs.size(), names.size());
  EXPECT_EQ(hrefs[0], "./javascript%3Aalert%281%29/view.html");
  EXPECT_EQ(hrefs[2], "./a%20b%23c%3Fd%25e/view.html");
  EXPECT_EQ(hrefs[3], "./caf%C3%A9/view.html");
  for (const std::string& href : hrefs) {
    EXPECT_EQ(href.compare(0, 2, "./"), 0) << href;
    EXPECT_EQ(href.find_first_of(":<>\"' #?"), std::string::npos) << href;
  }
  EXPECT_THAT(html, Not(HasSubstr("<script>")));
  EXPECT_THAT(html, HasSubstr("&quot;&gt;&lt;script&gt;"));  // The name shown as text.
}

TEST(BatchSummary, GateFailedAndPendingTakes) {
  BatchResult result;
  result.takes = {Ended("ok", "done"), Ended("gate", "gate_failed"), Ended("bad", "failed", ""), TakeOutcome()};
  result.done = 1;
  result.failed = 2;
  result.gate_failed = 1;
  const std::string json = FormatSummaryJson(result, "1.0");
  EXPECT_THAT(json, HasSubstr("\"status\": \"gate_failed\""));
  EXPECT_THAT(json, HasSubstr("\"gate_failed\": 1"));
  EXPECT_THAT(json, HasSubstr("\"pending\": 1"));
  const std::string csv = FormatSummaryCsv(result);
  EXPECT_THAT(csv, HasSubstr("\ngate,gate_failed,1,3,"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);  // Header and the three ended takes.
  const std::string html = FormatSummaryHtml(result);
  EXPECT_THAT(html, HasSubstr("<tr class=\"gate_failed\">"));
  EXPECT_THAT(html, HasSubstr("1 pending of 4 takes"));
}

TEST(BatchSummary, TheJsonIsWrittenAfterTheCsvAndHtml) {
  const std::string dir = testing::TempPath("summaries");
  ASSERT_EQ(::mkdir(dir.c_str(), 0755), 0);
  BatchResult result;
  result.takes = {Ended("ok", "done")};
  result.done = 1;
  // A folder where the page goes: its write fails, and the JSON must not have come first.
  ASSERT_EQ(::mkdir((dir + "/summary.html").c_str(), 0755), 0);
  EXPECT_FALSE(WriteBatchSummary(dir, result, "1.0", "summary").ok());
  EXPECT_TRUE(testing::FileExists(dir + "/summary.csv"));
  EXPECT_FALSE(testing::FileExists(dir + "/summary.json"));
  ASSERT_EQ(::rmdir((dir + "/summary.html").c_str()), 0);
  EXPECT_TRUE(WriteBatchSummary(dir, result, "1.0", "summary").ok());
  EXPECT_TRUE(testing::FileExists(dir + "/summary.json"));
  EXPECT_TRUE(testing::FileExists(dir + "/summary.html"));
}

}  // namespace
}  // namespace mocapsolve
