// Smoke tests of every `mocapsolve` command on small inputs the project makes itself,
// and the bad-input corpus: every file in tests/data/bad must give exit code 1 and a
// one-line error naming the file, never a crash or a partial output.
#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/motion_file.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

int CountLines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk.bvh");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=30 --fps=30", &output), 0) << output;
  }
  std::string demo_;
};

TEST_F(Cli, HelpListsCommandsAndFlags) {
  std::string output;
  EXPECT_EQ(testing::RunCli("--help", &output), 0);
  for (const char* command : {"info", "convert", "fk", "generate", "bench"}) {
    EXPECT_THAT(output, HasSubstr(command));
  }
  EXPECT_EQ(testing::RunCli("convert --help", &output), 0);
  EXPECT_THAT(output, HasSubstr("--euler_order"));
  EXPECT_THAT(output, HasSubstr("--scale"));
  EXPECT_THAT(output, ::testing::Not(HasSubstr("--demo_out")));  // Another command's flag.
  EXPECT_EQ(testing::RunCli("nonsense", &output), 1);
  EXPECT_THAT(output, HasSubstr("unknown command"));
}

TEST_F(Cli, Info) {
  std::string output;
  const std::string report = testing::TempPath("info.json");
  ASSERT_EQ(testing::RunCli("info " + demo_ + " --report=" + report, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("joints:    20"));
  EXPECT_THAT(output, HasSubstr("30 at 30 fps"));
  std::ifstream in(report);
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(json, HasSubstr("\"frames\": 30"));
}

TEST_F(Cli, ConvertAndFk) {
  std::string output;
  const std::string converted = testing::TempPath("xyz.bvh");
  ASSERT_EQ(testing::RunCli("convert " + demo_ + " " + converted + " --euler_order=XYZ --scale=0.01", &output), 0) << output;
  std::ifstream bvh(converted);
  const std::string text((std::istreambuf_iterator<char>(bvh)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("Xrotation Yrotation Zrotation"));

  const std::string csv_a = testing::TempPath("a.csv"), csv_b = testing::TempPath("b.csv");
  ASSERT_EQ(testing::RunCli("fk --quiet --motion=" + demo_ + " --out=" + csv_a, &output), 0) << output;
  ASSERT_EQ(testing::RunCli("fk --quiet --motion=" + converted + " --out=" + csv_b, &output), 0) << output;
  std::ifstream a(csv_a), b(csv_b);
  std::string line_a, line_b;
  std::getline(a, line_a);
  EXPECT_EQ(line_a, "frame,joint,x,y,z");
  std::getline(b, line_b);
  int rows = 0;
  while (std::getline(a, line_a) && std::getline(b, line_b)) {
    // Same joints in the same order; positions scaled by 0.01 (to 1e-6 cm of printing).
    const auto split = [](const std::string& line) {
      std::vector<std::string> cells;
      std::stringstream ss(line);
      std::string cell;
      while (std::getline(ss, cell, ',')) cells.push_back(cell);
      return cells;
    };
    const auto ca = split(line_a), cb = split(line_b);
    ASSERT_EQ(ca.size(), 5u);
    ASSERT_EQ(cb.size(), 5u);
    EXPECT_EQ(ca[1], cb[1]);
    for (int k = 2; k < 5; ++k) EXPECT_NEAR(std::stod(ca[k]) * 0.01, std::stod(cb[k]), 1e-5);
    ++rows;
  }
  EXPECT_EQ(rows, 30 * 20);
}

TEST_F(Cli, RefusesToOverwriteInputsAndBadFlags) {
  std::string output;
  EXPECT_EQ(testing::RunCli("convert " + demo_ + " " + demo_, &output), 1);
  EXPECT_THAT(output, HasSubstr("overwrite"));
  EXPECT_EQ(testing::RunCli("convert " + demo_ + " out.bvh --euler_order=XXY", &output), 1);
  EXPECT_EQ(CountLines(output), 1) << output;
  EXPECT_EQ(testing::RunCli("fk --motion=" + demo_, &output), 1);
  EXPECT_THAT(output, HasSubstr("--out"));
  EXPECT_EQ(testing::RunCli("info /nonexistent/file.bvh", &output), 1);
  EXPECT_THAT(output, HasSubstr("/nonexistent/file.bvh"));
}

TEST_F(Cli, BenchHarness) {
  std::string output;
  const std::string json = testing::TempPath("bench.json");
  ASSERT_EQ(testing::RunCli("bench --problem=fk --repeats=1 --bench_motion=" + demo_ + " --json=" + json, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("JSON {\"problem\": \"fk\""));
  EXPECT_TRUE(testing::FileExists(json));
  EXPECT_EQ(testing::RunCli("bench --problem=nope", &output), 1);
  EXPECT_THAT(output, HasSubstr("known: fk"));
}

// Issue 15: the commands that ran on the deep BVH, and the flags that took NaN or
// negative values, now refuse them with one line.
TEST_F(Cli, HostileFilesAndFlags) {
  std::string output;
  const std::string deep = testing::SourcePath("tests/data/bad/bad_deep_nesting.bvh");
  EXPECT_EQ(testing::RunCli("convert " + deep + " " + testing::TempPath("deep_out.bvh"), &output), 1);
  EXPECT_EQ(CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("bad_deep_nesting.bvh"));
  EXPECT_FALSE(testing::FileExists(testing::TempPath("deep_out.bvh")));
  const std::string huge = testing::SourcePath("tests/data/bad/bad_huge_coordinate.trc");
  EXPECT_EQ(testing::RunCli("filter --markers=" + huge + " --out=" + testing::TempPath("f.trc"), &output), 1);
  EXPECT_THAT(output, HasSubstr("beyond +-1e9"));
  EXPECT_EQ(testing::RunCli("propagate --motion=" + demo_ + " --out=" + testing::TempPath("p.bvh") +
                                " --ik_target=Hips:0,0,0 --frame=-5",
                            &output),
            1);
  EXPECT_THAT(output, HasSubstr("--frame"));
  EXPECT_EQ(CountLines(output), 1) << output;
}

// Every file in tests/data/bad: exit 1, one line naming the file, no output written.
TEST(CliBadInput, EveryBadFileGetsAOneLineError) {
  const std::string dir = testing::SourcePath("tests/data/bad");
  DIR* handle = ::opendir(dir.c_str());
  ASSERT_NE(handle, nullptr) << dir;
  std::vector<std::string> files;
  while (dirent* entry = ::readdir(handle)) {
    const std::string name = entry->d_name;
    if (name.rfind("bad_", 0) == 0) files.push_back(name);
  }
  ::closedir(handle);
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 5u);
  // The good pair the bad ones are read against must itself load.
  std::string ok_output;
  ASSERT_EQ(testing::RunCli("info " + dir + "/tiny_ok.amc --skeleton=" + dir + "/tiny_ok.asf", &ok_output), 0) << ok_output;
  for (const std::string& name : files) {
    const std::string path = dir + "/" + name;
    const std::string ext = FileExtension(name);
    std::string command;
    if (ext == ".bvh") {
      command = "fk --quiet --motion=" + path + " --out=" + testing::TempPath(name + ".csv");
    } else if (ext == ".amc") {
      command = "fk --quiet --motion=" + path + " --skeleton=" + dir + "/tiny_ok.asf --out=" +
                testing::TempPath(name + ".csv");
    } else if (ext == ".asf") {
      command = "info " + dir + "/tiny_ok.amc --skeleton=" + path;
    } else if (ext == ".json") {
      // Marker sets, read against a generated demo clip (made once; its own output must
      // not name the bad file, so the error has to).
      static std::string demo;
      if (demo.empty()) {
        demo = testing::TempPath("markerset_demo.bvh");
        std::string generated;
        EXPECT_EQ(testing::RunCli("generate --demo_out=" + demo + " --frames=5 --fps=30", &generated), 0) << generated;
      }
      command = "markers --quiet --motion=" + demo + " --markerset=" + path + " --out=" +
                testing::TempPath("markers_from_bad_set.c3d");
    } else {
      command = "info " + path;
    }
    std::string output;
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(testing::RunCli(command, &output), 1) << name << ": " << output;
    // Hostile files (make_bad_hostile.py) must be cheap to refuse: a generous bound, far
    // below the minutes (or crash) they took before issue 15.
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0)
        << name;
    EXPECT_LT(output.size(), 1000u) << name << ": names in messages are cut";
    EXPECT_EQ(CountLines(output), 1) << name << ": " << output;
    EXPECT_THAT(output, HasSubstr(name)) << command;
    EXPECT_FALSE(testing::FileExists(testing::TempPath(name + ".csv"))) << name << ": partial output";
  }
}

}  // namespace
}  // namespace mocapsolve
