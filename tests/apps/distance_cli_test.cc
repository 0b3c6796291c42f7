// Smoke tests of `mocapsolve distance` on the project's demo clip: the CSV, plot and report
// it writes, and the bad-input cases that must fail with one line.
#include <algorithm>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

class DistanceCli : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk.bvh");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=120 --fps=30", &output), 0)
        << output;
  }
  std::string demo_;
};

TEST_F(DistanceCli, WritesCurvePlotAndReport) {
  const std::string csv = testing::TempPath("curve.csv");
  const std::string svg = testing::TempPath("curve.svg");
  const std::string report = testing::TempPath("distance.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("distance --motion=" + demo_ + " --frame=40 --method=green,diffusion,isomap"
                            " --region=5:110 --out=" + csv + " --plot=" + svg + " --report=" + report,
                            &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("period 33 frames"));  // The demo cycle: 1.1 s at 30 fps.
  std::istringstream lines(testing::ReadTextFile(csv));
  std::string line;
  ASSERT_TRUE(std::getline(lines, line));
  EXPECT_EQ(line, "frame,distance,weight,diffusion_distance,isomap_distance");
  int rows = 0;
  while (std::getline(lines, line)) {
    double frame, distance, weight;
    char comma;
    std::istringstream row(line);
    ASSERT_TRUE(row >> frame >> comma >> distance >> comma >> weight) << line;
    EXPECT_EQ(frame, rows);
    EXPECT_GE(weight, 0.0);
    EXPECT_LE(weight, 1.0);
    if (rows == 40) {
      EXPECT_EQ(weight, 1.0);
    }
    if (rows < 5 || rows >= 110) {
      EXPECT_EQ(distance, 1.0);
    }
    ++rows;
  }
  EXPECT_EQ(rows, 120);
  EXPECT_THAT(testing::ReadTextFile(svg), HasSubstr("<svg"));
  const std::string json = testing::ReadTextFile(report);
  for (const char* key : {"\"sigma_used\"", "\"eigenpairs_used\": 10", "\"build_ms\"", "\"second_difference\"",
                          "\"same_phase_weights\"", "\"period_frames\": 33", "\"kernel\": \"dense\""}) {
    EXPECT_THAT(json, HasSubstr(key));
  }
}

TEST_F(DistanceCli, BadInputsFailWithOneLine) {
  const std::string out = testing::TempPath("bad.csv");
  std::string output;
  struct Case {
    std::string arguments, expected;
  };
  const std::vector<Case> cases = {
      {"distance --motion=" + demo_ + " --out=" + out, "--frame"},
      {"distance --motion=" + demo_ + " --frame=500 --out=" + out, "--frame"},
      {"distance --motion=" + demo_ + " --frame=5 --method=pca --out=" + out, "--method"},
      {"distance --motion=" + demo_ + " --frame=5 --region=50:10 --out=" + out, "--region"},
      {"distance --motion=" + demo_ + " --frame=5 --region=10:50 --out=" + out, "outside the region"},
      {"distance --motion=" + demo_ + " --frame=5 --sigma=-2 --out=" + out, "--sigma"},
      {"distance --motion=" + demo_ + " --frame=5 --falloff_kernel=sparse --eigenpairs=0 --out=" + out, "eigenpairs"},
      {"distance --motion=" + demo_ + " --frame=5 --feature_joints=Tail --out=" + out, "Tail"},
      {"distance --motion=" + demo_ + " --frame=5 --sweep=1,x --out=" + out, "--sweep"},
      {"distance --motion=" + demo_ + " --frame=5 --out=" + testing::TempPath("bad.txt"), "csv"},
      {"distance --motion=/nonexistent.bvh --frame=5 --out=" + out, "/nonexistent.bvh"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(testing::RunCli(c.arguments, &output), 1) << c.arguments << "\n" << output;
    EXPECT_THAT(output, HasSubstr(c.expected)) << c.arguments;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  }
  EXPECT_FALSE(testing::FileExists(out));
}

}  // namespace
}  // namespace mocapsolve
