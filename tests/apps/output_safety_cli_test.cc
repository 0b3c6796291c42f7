// Outputs never overwrite inputs or each other, through every output flag (issue 15's
// data-loss cases): --report and --plot onto an input, two outputs on one path, a
// character device as --report. Each refused run exits 1 with one line and leaves the
// files as they were.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

class OutputSafety : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk.bvh");
    markers_ = testing::TempPath("walk.c3d");
    set_ = testing::TempPath("set.json");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=20 --fps=30", &output), 0) << output;
    ASSERT_EQ(testing::RunCli("markers --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 "
                              "--write_markerset=" + set_ + " --out=" + markers_, &output), 0) << output;
  }
  // Runs a command that must be refused: exit 1, one line naming `named`, and every
  // input unchanged.
  void ExpectRefused(const std::string& arguments, const std::string& named) {
    const std::string before_demo = testing::ReadTextFile(demo_), before_markers = testing::ReadTextFile(markers_),
                      before_set = testing::ReadTextFile(set_);
    std::string output;
    EXPECT_EQ(testing::RunCli(arguments, &output), 1) << arguments << "\n" << output;
    EXPECT_THAT(output, HasSubstr(named)) << arguments;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
    EXPECT_EQ(testing::ReadTextFile(demo_), before_demo) << arguments;
    EXPECT_EQ(testing::ReadTextFile(markers_), before_markers) << arguments;
    EXPECT_EQ(testing::ReadTextFile(set_), before_set) << arguments;
  }
  std::string Solve() const {
    return "solve --quiet --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
           " --markerset=" + set_ + " ";
  }
  std::string demo_, markers_, set_;
};

TEST_F(OutputSafety, ReportAndPlotNeverOverwriteAnInput) {
  for (const std::string* input : {&set_, &demo_, &markers_}) {
    ExpectRefused(Solve() + "--out=" + testing::TempPath("o.bvh") + " --report=" + *input,
                  "names the same file as --");
    ExpectRefused(Solve() + "--out=" + testing::TempPath("o.bvh") + " --plot=" + *input,
                  "names the same file as --");
  }
  EXPECT_FALSE(testing::FileExists(testing::TempPath("o.bvh")));  // Nothing partial either.
  ExpectRefused("info " + demo_ + " --report=" + demo_, "names the same file as " + demo_);
  ExpectRefused("fk --quiet --motion=" + demo_ + " --out=" + testing::TempPath("p.csv") + " --report=" + demo_,
                "names the same file as --motion");
  ExpectRefused("filter --quiet --motion=" + demo_ + " --out=" + testing::TempPath("f.bvh") + " --report=" + demo_,
                "names the same file as --motion");
  // Through another name (a symlink).
  const std::string link = testing::TempPath("link.json");
  ASSERT_EQ(::symlink(set_.c_str(), link.c_str()), 0);
  ExpectRefused(Solve() + "--out=" + testing::TempPath("o2.bvh") + " --report=" + link,
                "names the same file as --markerset");
  EXPECT_FALSE(testing::FileExists(testing::TempPath("o2.bvh")));
}

TEST_F(OutputSafety, TwoOutputsOnOnePathAreRefused) {
  const std::string out = testing::TempPath("x.bvh");
  ExpectRefused(Solve() + "--out=" + out + " --report=" + out, "names the same file as --out");
  EXPECT_FALSE(testing::FileExists(out));
  const std::string csv = testing::TempPath("x.csv");
  ExpectRefused("fk --quiet --motion=" + demo_ + " --out=" + csv + " --report=" + csv, "names the same file as --out");
  EXPECT_FALSE(testing::FileExists(csv));
}

TEST_F(OutputSafety, ACharacterDeviceIsWrittenIntoNotReplaced) {
  std::string output;
  ASSERT_EQ(testing::RunCli("info " + demo_ + " --report=/dev/null", &output), 0) << output;
  struct stat st;
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  // A full disk is an error naming the file, and the command's other outputs do not appear.
  const std::string out = testing::TempPath("full.bvh");
  EXPECT_EQ(testing::RunCli(Solve() + "--out=" + out + " --report=/dev/full", &output), 1) << output;
  EXPECT_THAT(output, HasSubstr("/dev/full"));
  EXPECT_FALSE(testing::FileExists(out));
}

// A failed run still answers --report (issue 17): status, command, version, message;
// its other outputs do not appear.
TEST_F(OutputSafety, FailedRunWritesAnErrorReport) {
  const std::string report = testing::TempPath("failed.json"), out = testing::TempPath("never.bvh");
  const std::string missing = testing::TempPath("missing.c3d");
  std::string output;
  EXPECT_EQ(testing::RunCli("solve --quiet --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + missing +
                            " --markerset=" + set_ + " --out=" + out + " --report=" + report, &output), 1);
  const std::string json = testing::ReadTextFile(report);
  EXPECT_THAT(json, HasSubstr("\"status\": \"error\""));
  EXPECT_THAT(json, HasSubstr("\"command\": \"solve\""));
  EXPECT_THAT(json, HasSubstr("\"version\""));
  EXPECT_THAT(json, HasSubstr("missing.c3d"));
  EXPECT_THAT(json, HasSubstr("\"stage\": \"inputs\""));  // Where it failed.
  EXPECT_FALSE(testing::FileExists(out));
  // A flag refused before any work fails in the "arguments" stage.
  EXPECT_EQ(testing::RunCli("solve --quiet --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                            " --markerset=" + set_ + " --out=" + out + " --report=" + report + " --out=" + set_, &output), 1);
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"stage\": \"run\""));
  // Never onto an input, even when failing.
  const std::string before = testing::ReadTextFile(set_);
  EXPECT_EQ(testing::RunCli("solve --quiet --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + missing +
                            " --markerset=" + set_ + " --report=" + set_, &output), 1);
  EXPECT_EQ(testing::ReadTextFile(set_), before);
}

// "-" is the standard output for text outputs (issue 17): the data alone goes to stdout,
// the command's messages to stderr; binary outputs and two outputs on "-" are refused.
TEST_F(OutputSafety, DashWritesTextOutputsToStandardOutput) {
  const std::string err = testing::TempPath("stderr.txt");
  auto run_split = [&](const std::string& arguments, std::string* out) {
    return testing::RunProgram("/bin/sh", "-c '" + testing::CliPath() + " " + arguments + " 2>" + err + "'", out);
  };
  std::string out;
  ASSERT_EQ(run_split("fk --motion=" + demo_ + " --out=-", &out), 0) << testing::ReadTextFile(err);
  EXPECT_THAT(out, ::testing::StartsWith("frame,joint,x,y,z\n"));
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1 + 20 * 20) << out.substr(0, 200);  // 20 frames x 20 joints.
  EXPECT_THAT(out, ::testing::Not(HasSubstr("wrote")));
  EXPECT_THAT(testing::ReadTextFile(err), HasSubstr("wrote -"));

  const std::string report = testing::TempPath("dash_report.json");
  ASSERT_EQ(run_split(Solve() + "--out=- --report=" + report, &out), 0) << testing::ReadTextFile(err);
  EXPECT_THAT(out, ::testing::StartsWith("HIERARCHY\n"));
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"out\": \"-\""));

  // A failure report on stdout, nothing else there.
  EXPECT_EQ(run_split("fk --motion=" + testing::TempPath("missing.bvh") + " --out=x.csv --report=-", &out), 1);
  EXPECT_THAT(out, ::testing::StartsWith("{"));
  EXPECT_THAT(out, HasSubstr("\"status\": \"error\""));
  EXPECT_THAT(out, HasSubstr("\"stage\": \"run\""));

  ExpectRefused("markers --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 --out=-", "-");
  ExpectRefused(Solve() + "--out=- --report=-", "--report=-");
}

TEST(Help, DefaultsAreWrittenAsPeopleWriteThem) {
  std::string output;
  ASSERT_EQ(testing::RunCli("solve --help", &output), 0);
  EXPECT_THAT(output, HasSubstr("--function_tolerance (double) default: 1e-06"));
  EXPECT_THAT(output, ::testing::Not(HasSubstr("9.9999999999999995e-07")));
  ASSERT_EQ(testing::RunCli("--version", &output), 0);
  EXPECT_THAT(output, ::testing::StartsWith("mocapsolve "));
}

}  // namespace
}  // namespace mocapsolve
