// What the CLI prints, and where: names from a file are escaped for the terminal
// (TerminalText), a failed write of stdout is an error, inputs that are not regular
// files are refused rather than waited on, and a subject's numbers are checked when read.
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/trc_writer.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

int CountLines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

// `info` printed a label holding ESC raw: "\x1b[2J" cleared the user's terminal.
TEST(TerminalOutput, InfoEscapesControlCharactersInLabels) {
  MarkerTrajectories take({"LASI\x1b[2J", "R\x7f" "ASI", "caf\xc3\xa9"}, 2);
  take.frame_rate = 100.0;
  take.unit = LengthUnitFromName("mm");
  take.SetSample(0, 0, Eigen::Vector3d(1, 2, 3));
  const std::string path = testing::TempPath("escape.trc");
  ASSERT_TRUE(WriteTrc(path, take).ok());
  std::string output;
  ASSERT_EQ(testing::RunCli("info " + path, &output), 0) << output;
  EXPECT_EQ(output.find('\x1b'), std::string::npos) << output;
  EXPECT_EQ(output.find('\x7f'), std::string::npos) << output;
  EXPECT_THAT(output, HasSubstr("LASI\\x1b[2J"));
  EXPECT_THAT(output, HasSubstr("R\\x7fASI"));
  EXPECT_THAT(output, HasSubstr("caf\xc3\xa9"));  // UTF-8 stays as it is.
}

// `info x.bvh > /dev/full` exited 0: what the command printed was lost without a word.
TEST(TerminalOutput, AFailedWriteOfStandardOutputIsAnError) {
  const std::string bvh = testing::SourcePath("tests/data/good/small.bvh");
  std::string output;
  // Braces: stdout to /dev/full, stderr (RunProgram's 2>&1) to the test.
  EXPECT_EQ(testing::RunProgram(std::string("{ ") + testing::CliPath(), "info " + bvh + " > /dev/full; }", &output), 1);
  EXPECT_THAT(output, HasSubstr("writing the standard output failed (No space left on device)"));
  EXPECT_EQ(CountLines(output), 1) << output;
}

// A FIFO given as input blocked `info` forever.
TEST(TerminalOutput, AFifoIsRefusedNotWaitedOn) {
  const std::string fifo = testing::TempPath("take.trc");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& command : {"info " + fifo, "convert " + fifo + " " + testing::TempPath("out.c3d")}) {
    std::string output;
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(testing::RunProgram(std::string("timeout -s KILL 20 ") + testing::CliPath(), command, &output), 1) << output;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
    EXPECT_THAT(output, HasSubstr(fifo + ": is not a regular file (a FIFO)"));
    EXPECT_EQ(CountLines(output), 1) << output;
  }
  EXPECT_FALSE(testing::FileExists(testing::TempPath("out.c3d")));
}

// A subject with "scale": 1e308 made every sample infinite, and the solve reported "no
// marker observed in any frame"; now the subject's reader names the field.
TEST(TerminalOutput, SubjectNumbersAreCheckedWhenRead) {
  const std::string good = testing::SourcePath("tests/data/good");
  const std::string dir = testing::TempPath("");
  std::filesystem::copy_file(good + "/small.bvh", dir + "small.bvh");
  std::string subject = testing::ReadTextFile(good + "/subject.json");
  for (const auto& [from, to, field] : {std::make_tuple("\"scale\": 0", "\"scale\": 1e308", "marker_files.scale: 1e+308"),
                                        std::make_tuple("\"amc_fps\": 120", "\"amc_fps\": 1e-300", "amc_fps 1e-300")}) {
    std::string bad = subject;
    ASSERT_NE(bad.find(from), std::string::npos) << from;
    bad.replace(bad.find(from), std::string(from).size(), to);
    testing::WriteTextFile(dir + "bad_subject.json", bad);
    std::string output;
    EXPECT_EQ(testing::RunCli("solve --quiet --solver=dls --subject=" + dir + "bad_subject.json --markers=" + good +
                                  "/small.c3d --out=" + dir + "out.bvh",
                              &output),
              1);
    EXPECT_THAT(output, HasSubstr("bad_subject.json"));
    EXPECT_THAT(output, HasSubstr(field));
    EXPECT_THAT(output, Not(HasSubstr("no marker observed")));
    EXPECT_EQ(CountLines(output), 1) << output;
    EXPECT_FALSE(testing::FileExists(dir + "out.bvh"));
  }
}

}  // namespace
}  // namespace mocapsolve
