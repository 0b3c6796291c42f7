// `mocapsolve solve` end to end on inputs the project makes: the demo clip, markers
// synthesized from it, solved back by both solvers; and the bad inputs the issue names
// (labels missing from the marker set, a marker set for another skeleton).
#include <algorithm>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/bvh_reader.h"
#include "kinematics/forward_kinematics.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

class SolveCli : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk.bvh");
    markers_ = testing::TempPath("walk.c3d");
    set_ = testing::TempPath("set.json");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=40 --fps=30", &output), 0) << output;
    ASSERT_EQ(testing::RunCli("markers --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 "
                              "--write_markerset=" + set_ + " --out=" + markers_, &output), 0) << output;
  }
  std::string Solve(const std::string& extra, int* code) {
    std::string output;
    *code = testing::RunCli("solve --quiet --skeleton=" + demo_ + " --skeleton_units=cm --markers=" +
                            markers_ + " " + extra, &output);
    return output;
  }
  std::string demo_, markers_, set_;
};

TEST_F(SolveCli, BothSolversRecoverTheClip) {
  Skeleton skeleton;
  Motion truth;
  ASSERT_TRUE(ReadBvh(demo_, &skeleton, &truth).ok());
  for (const char* solver : {"ceres", "dls"}) {
    const std::string out = testing::TempPath(std::string(solver) + ".bvh");
    const std::string report = testing::TempPath(std::string(solver) + ".json");
    int code = 0;
    // No prior: noise-free markers are matched exactly.
    const std::string plot = testing::TempPath(std::string(solver) + ".svg");
    const std::string output = Solve("--markerset=" + set_ + " --out=" + out + " --solver=" + solver +
                                     " --prior_weight=0 --report=" + report + " --plot=" + plot, &code);
    ASSERT_EQ(code, 0) << output;
    EXPECT_THAT(output, HasSubstr("RMS marker residual"));
    Skeleton solved_skeleton;
    Motion solved;
    ASSERT_TRUE(ReadBvh(out, &solved_skeleton, &solved).ok());
    ASSERT_EQ(solved.num_frames(), truth.num_frames());
    FkData a(skeleton), b(skeleton);
    double worst = 0.0;
    for (int f = 0; f < truth.num_frames(); ++f) {
      ForwardKinematics(skeleton, truth.frames[f], &a);
      ForwardKinematics(solved_skeleton, solved.frames[f], &b);
      for (int j = 0; j < skeleton.num_joints(); ++j) {
        worst = std::max(worst, (a.world_positions[j] - b.world_positions[j]).norm());
      }
    }
    // C3D stores float32 mm and the BVH 6 digits: 0.01 cm (0.1 mm) is their rounding.
    EXPECT_LT(worst, 0.01) << solver;
    EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"rms_marker_residual\""));
    const std::string svg = testing::ReadTextFile(plot);
    EXPECT_THAT(svg, HasSubstr("<svg"));
    EXPECT_THAT(svg, HasSubstr("<polyline"));
  }
}

// --memory_mb with --mode=clip: the whole-clip problem's estimate (pipeline/memory_estimate.h:
// 23 MB + 184 KB per frame at 41 markers, scaled by the take's markers) over the limit is
// refused before any solve, with the figure; nothing written. The per-frame mode has no
// whole-clip problem and runs.
TEST_F(SolveCli, MemoryLimitRefusesTheClipSolve) {
  const std::string out = testing::TempPath("limited.bvh");
  int code = 0;
  std::string output = Solve("--markerset=" + set_ + " --out=" + out + " --mode=clip --memory_mb=20", &code);
  EXPECT_EQ(code, 1) << output;
  EXPECT_THAT(output, HasSubstr("--memory_mb=20: the clip solve on " + markers_ + " (40 frames, "));
  EXPECT_THAT(output, HasSubstr("MB (23 MB + "));
  EXPECT_FALSE(testing::FileExists(out));
  output = Solve("--markerset=" + set_ + " --out=" + out + " --memory_mb=20", &code);
  EXPECT_EQ(code, 0) << output;
  EXPECT_TRUE(testing::FileExists(out));
}

TEST_F(SolveCli, MarkerSetLabelMissingFromTheFile) {
  // Rename one marker of the set: the C3D has no column for it.
  std::string json = testing::ReadTextFile(set_);
  const size_t at = json.find("\"Hips_0\"");
  ASSERT_NE(at, std::string::npos);
  json.replace(at, 8, "\"NOPE_0\"");
  const std::string bad = testing::TempPath("bad_label.json");
  std::ofstream(bad) << json;
  int code = 0;
  const std::string output = Solve("--markerset=" + bad + " --out=" + testing::TempPath("o.bvh"), &code);
  EXPECT_EQ(code, 1);
  EXPECT_THAT(output, HasSubstr("NOPE_0"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
}

TEST_F(SolveCli, MarkerSetForAnotherSkeleton) {
  std::string json = testing::ReadTextFile(set_);
  const size_t at = json.find("\"joint\": \"Hips\"");
  ASSERT_NE(at, std::string::npos) << json.substr(0, 400);
  json.replace(at, 15, "\"joint\": \"Pelvis\"");
  const std::string bad = testing::TempPath("bad_joint.json");
  std::ofstream(bad) << json;
  int code = 0;
  const std::string output = Solve("--markerset=" + bad + " --out=" + testing::TempPath("o.bvh"), &code);
  EXPECT_EQ(code, 1);
  EXPECT_THAT(output, HasSubstr("Pelvis"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
}

TEST_F(SolveCli, RepairLeavesCleanMarkersAloneAndWritesTheReport) {
  const std::string out = testing::TempPath("repaired.c3d");
  const std::string report = testing::TempPath("repair.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("repair --quiet --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                            " --markerset=" + set_ + " --out_markers=" + out + " --out_motion=" +
                            testing::TempPath("repaired.bvh") + " --report=" + report, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("Marker Filling"));
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"timings\""));
  // Clean synthetic markers: nothing to repair, so the file comes back sample for sample.
  std::string info_in, info_out;
  ASSERT_EQ(testing::RunCli("info " + markers_, &info_in), 0);
  ASSERT_EQ(testing::RunCli("info " + out, &info_out), 0);
  EXPECT_EQ(info_in.substr(info_in.find("markers:")), info_out.substr(info_out.find("markers:")));
  // A skeleton whose unit is unknown cannot take cm thresholds.
  EXPECT_EQ(testing::RunCli("repair --skeleton=" + demo_ + " --markers=" + markers_ + " --markerset=" + set_ +
                            " --out_markers=" + testing::TempPath("x.c3d"), &output), 1);
  EXPECT_THAT(output, HasSubstr("--skeleton_units"));
}

TEST_F(SolveCli, CorruptThenRepair) {
  const std::string bad = testing::TempPath("bad.c3d"), mask = testing::TempPath("mask.csv");
  const std::string fixed = testing::TempPath("fixed.c3d");
  std::string output;
  ASSERT_EQ(testing::RunCli("corrupt --markers=" + markers_ + " --out=" + bad + " --mask_out=" + mask +
                            " --gaps=4 --gap_min=5 --gap_max=10 --swaps=0 --noisy_markers=0", &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("gap"));
  std::ifstream in(mask);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "frame,marker,kind");
  ASSERT_EQ(testing::RunCli("repair --quiet --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + bad +
                            " --markerset=" + set_ + " --out_markers=" + fixed + " --trim_max=5", &output), 0) << output;
  std::string info;
  ASSERT_EQ(testing::RunCli("info " + fixed, &info), 0);
  EXPECT_THAT(info, HasSubstr("missing:   0 of"));  // Every gap refilled.
  EXPECT_EQ(testing::RunCli("corrupt --markers=" + bad + " --out=" + bad, &output), 1);
}

TEST_F(SolveCli, EvaluatePrintsTheTableAndTheReport) {
  const std::string report = testing::TempPath("evaluate.json"), csv = testing::TempPath("evaluate.csv");
  std::string output;
  ASSERT_EQ(testing::RunCli("evaluate --quiet --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                            " --markerset=" + set_ + " --gaps=3 --gap_min=5 --gap_max=10 --trim_max=5" +
                            " --report=" + report + " --table_csv=" + csv, &output), 0) << output;
  for (const char* method : {"| original |", "| polynomial |", "| linear |", "| pca |", "| reference only |",
                             "| ours |"}) {
    EXPECT_THAT(output, HasSubstr(method));
  }
  EXPECT_THAT(testing::ReadTextFile(report), HasSubstr("\"position_error_ratio_to_ours\""));
  EXPECT_THAT(testing::ReadTextFile(csv), HasSubstr("trial,seed,method,joint_position_cm"));
  // Bad flags give one line and exit code 1.
  EXPECT_EQ(testing::RunCli("evaluate --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                            " --markerset=" + set_ + " --gap_min=0", &output), 1);
  EXPECT_THAT(output, HasSubstr("--gap_min"));
  EXPECT_EQ(testing::RunCli("evaluate --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                            " --markerset=" + set_ + " --reference=magic", &output), 1);
  EXPECT_THAT(output, HasSubstr("--reference"));
}

TEST_F(SolveCli, ResidualsCsvHasOneRowPerFrame) {
  for (const char* mode : {"frame", "clip"}) {
    const std::string csv = testing::TempPath(std::string("residuals_") + mode + ".csv");
    int code = 0;
    const std::string output = Solve(std::string("--markerset=") + set_ + " --solver=dls --mode=" + mode +
                                     " --out=" + testing::TempPath("r.bvh") + " --residuals_csv=" + csv, &code);
    ASSERT_EQ(code, 0) << output;
    std::istringstream lines(testing::ReadTextFile(csv));
    std::string line;
    std::getline(lines, line);
    EXPECT_EQ(line, "frame,time_s,markers_observed,rms_mm,max_mm");
    int rows = 0;
    while (std::getline(lines, line)) {
      int frame = -1, observed = 0;
      double time = -1, rms = -1, max = -1;
      ASSERT_EQ(std::sscanf(line.c_str(), "%d,%lf,%d,%lf,%lf", &frame, &time, &observed, &rms, &max), 5) << line;
      EXPECT_EQ(frame, rows);
      EXPECT_NEAR(time, rows / 30.0, 1e-5);
      EXPECT_GT(observed, 0);
      EXPECT_LE(rms, max + 1e-12);
      EXPECT_LT(max, 5.0) << line;  // mm: the markers are the clip's own (noise-free).
      ++rows;
    }
    EXPECT_EQ(rows, 40) << mode;
  }
}

TEST_F(SolveCli, EvaluateLeaveOneOutPredictsEveryMarker) {
  const std::string report = testing::TempPath("loo.json"), csv = testing::TempPath("loo.csv");
  std::string output;
  for (const char* mode : {"frame", "clip"}) {
    ASSERT_EQ(testing::RunCli(std::string("evaluate --quiet --method=leave_one_out --mode=") + mode +
                              " --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                              " --markerset=" + set_ + " --report=" + report + " --table_csv=" + csv, &output), 0)
        << output;
    EXPECT_THAT(output, HasSubstr("| marker | samples | mean | median | 95th pct | max |"));
    EXPECT_THAT(output, HasSubstr("| all |"));
    const std::string json = testing::ReadTextFile(report);
    EXPECT_THAT(json, HasSubstr("\"method\": \"leave_one_out\""));
    EXPECT_THAT(json, HasSubstr(std::string("\"mode\": \"") + mode + "\""));
    EXPECT_THAT(json, HasSubstr("\"per_marker\""));
    EXPECT_THAT(testing::ReadTextFile(csv), HasSubstr("marker,samples,mean,median,p95,max,unit"));
  }
  EXPECT_EQ(testing::RunCli("evaluate --method=guess --skeleton=" + demo_ + " --skeleton_units=cm --markers=" +
                            markers_ + " --markerset=" + set_, &output), 1);
  EXPECT_THAT(output, HasSubstr("--method: unknown 'guess' (repair, leave_one_out, small_errors, retarget)"));
}

TEST_F(SolveCli, EvaluateSmallErrorsReportsRecallAndPrecision) {
  const std::string report = testing::TempPath("small.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("evaluate --quiet --method=small_errors --trials=2 --white_noise_mm=1 --skeleton=" +
                            demo_ + " --skeleton_units=cm --markers=" + markers_ + " --markerset=" + set_ +
                            " --report=" + report, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("| seed | damaged | flagged | found | recall | precision |"));
  EXPECT_THAT(output, HasSubstr("flagged on the undamaged take (seed 1):"));
  const std::string json = testing::ReadTextFile(report);
  for (const char* key : {"\"recall\"", "\"precision\"", "\"precision_without_own\"", "\"own\"", "\"seeds\""}) {
    EXPECT_THAT(json, HasSubstr(key));
  }
  EXPECT_EQ(testing::RunCli("evaluate --method=small_errors --white_noise_mm=-1 --skeleton=" + demo_ +
                            " --skeleton_units=cm --markers=" + markers_ + " --markerset=" + set_, &output), 1);
  EXPECT_THAT(output, HasSubstr("--white_noise_mm"));
}

// Progress when stderr is not a terminal (a log file, as here): plain lines, no carriage
// returns piling up on one line; the last state once.
TEST_F(SolveCli, ProgressInALogIsPlainLines) {
  std::string output;
  ASSERT_EQ(testing::RunCli("solve --solver=dls --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                            " --markerset=" + set_ + " --out=" + testing::TempPath("logged.bvh"), &output), 0) << output;
  EXPECT_EQ(output.find('\r'), std::string::npos) << output;
  const size_t line = output.find("solve (dls): ");
  ASSERT_NE(line, std::string::npos) << output;
  EXPECT_EQ(output.find("solve (dls): ", line + 1), std::string::npos) << output;  // A short run: the last state only.
  EXPECT_THAT(output.substr(line, output.find('\n', line) - line), HasSubstr("ETA 0.0 s"));
}

TEST_F(SolveCli, FitSkeletonWritesTheSkeletonAndTheMarkerSet) {
  const std::string bvh = testing::TempPath("fitted.bvh"), set = testing::TempPath("fitted.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("fit_skeleton --quiet --solver=dls --fit_iterations=2 --skeleton=" + demo_ +
                            " --skeleton_units=cm --markers=" + markers_ + " --markerset=" + set_ + " --out=" + bvh +
                            " --out_markerset=" + set, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("marker RMS"));
  EXPECT_THAT(output, HasSubstr("checks: marker RMS"));
  EXPECT_THAT(output, ::testing::Not(HasSubstr("round 0:")));  // --quiet silences the rounds.
  // The fitted pair solves the markers again.
  ASSERT_EQ(testing::RunCli("solve --quiet --skeleton=" + bvh + " --skeleton_units=cm --markers=" + markers_ +
                            " --markerset=" + set + " --out=" + testing::TempPath("refit.bvh"), &output), 0) << output;
  EXPECT_EQ(testing::RunCli("fit_skeleton --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                            " --markerset=" + set_ + " --out=" + bvh + " --out_markerset=" + bvh, &output), 1);
  EXPECT_THAT(output, HasSubstr("expected a .json"));
  // A label map naming a label the take lacks: one line, exit 1.
  EXPECT_EQ(testing::RunCli("fit_skeleton --skeleton=" + demo_ + " --skeleton_units=cm --markers=" + markers_ +
                            " --markerset=" + set_ + " --out=" + bvh + " --template_labels=Hips_0:NOPE", &output), 1);
  EXPECT_EQ(output, "mocapsolve fit_skeleton: --template_labels: NOPE (for Hips_0) is not in " + markers_ + "\n");
}

}  // namespace
}  // namespace mocapsolve
