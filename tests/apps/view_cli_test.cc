// `mocapsolve view` and --view pages: their bad inputs (one line, exit 1, no page), and
// the pages themselves opened in headless Chromium (scripts/view_check.sh): no console
// errors, a canvas that is not blank, two frames of a moving take that differ and one
// frame drawn twice the same, a repaired marker in its reason's colour at a frame the
// repair report names. The browser part skips when chromium, node or the npm packages
// are unavailable (exit 77), and fails instead under MOCAPSOLVE_REQUIRE_DATA=1.
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/json_reader.h"
#include "tests/gltf_test_files.h"
#include "tests/test_support.h"
#include "viewer/view_page.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

bool RuntimeInstalled() {
  std::string path;
  return FindViewerRuntime(&path).ok();
}

#define MOCAPSOLVE_NEED_VIEWER_RUNTIME()                                                          \
  if (!RuntimeInstalled()) {                                                                      \
    if (testing::DataRequired()) FAIL() << "viewer runtime missing (scripts/viewer_tools.sh)";    \
    GTEST_SKIP() << "viewer runtime not installed (scripts/viewer_tools.sh)";                     \
  }

// Runs scripts/view_check.sh on a spec; skips on exit 77 (unless data are required).
struct BrowserRun {
  int code = -1;
  std::string output;
};
BrowserRun RunViewCheck(const std::string& spec_json) {
  const std::string spec = testing::TempPath("view_check.json");
  FILE* file = std::fopen(spec.c_str(), "w");
  std::fputs(spec_json.c_str(), file);
  std::fclose(file);
  const std::string log = testing::TempPath("view_check.log");
  const int raw = std::system((testing::SourcePath("scripts/view_check.sh") + " " + spec + " > " + log + " 2>&1").c_str());
  BrowserRun run;
  run.code = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.output = testing::ReadTextFile(log);
  std::printf("%s", run.output.c_str());
  return run;
}

#define MOCAPSOLVE_CHECK_IN_BROWSER(spec)                                                        \
  const BrowserRun run = RunViewCheck(spec);                                                     \
  if (run.code == 77) {                                                                          \
    if (testing::DataRequired()) FAIL() << "browser unavailable: " << run.output;                \
    GTEST_SKIP() << "browser unavailable: " << run.output;                                       \
  }                                                                                              \
  EXPECT_EQ(run.code, 0) << run.output;

// The first interval a repair report filled: its marker, a frame inside it, and the state
// the page must show there (the reason of the detected interval of that marker that
// overlaps it most, as repair_intervals.h defines).
struct Repaired {
  std::string label, state;
  int frame = -1;
};
Repaired FirstRepaired(const std::string& report_path) {
  Repaired out;
  JsonNode root;
  if (!ReadJsonFile(report_path, &root).ok()) return out;
  const JsonNode* filled = root.Find("filled");
  const JsonNode* detected = root.Find("detected");
  if (filled == nullptr || filled->items.empty() || detected == nullptr) return out;
  const JsonNode& fill = filled->items[0];
  out.label = fill.Find("marker")->string;
  const int first = static_cast<int>(fill.Find("first_frame")->number);
  const int last = static_cast<int>(fill.Find("last_frame")->number);
  out.frame = (first + last) / 2;
  out.state = "gap";  // Unless a detected interval of the marker overlaps: the one overlapping most.
  double best = 0;
  for (const JsonNode& d : detected->items) {
    if (d.Find("marker")->string != out.label) continue;
    const double overlap = std::min<double>(d.Find("last_frame")->number, last) -
                           std::max<double>(d.Find("first_frame")->number, first) + 1;
    if (overlap <= best) continue;
    best = overlap;
    const std::string what = d.Find("what")->string;
    out.state = what == "missing" ? "gap" : what;
  }
  return out;
}

class ViewCli : public ::testing::Test {
 protected:
  void SetUp() override {
    demo_ = testing::TempPath("walk.bvh");
    clean_ = testing::TempPath("walk.c3d");
    damaged_ = testing::TempPath("damaged.c3d");
    set_ = testing::TempPath("set.json");
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo_ + " --frames=90 --fps=30", &output), 0) << output;
    ASSERT_EQ(testing::RunCli("markers --motion=" + demo_ + " --skeleton_units=cm --markerset=auto:3 "
                              "--write_markerset=" + set_ + " --out=" + clean_, &output), 0) << output;
    ASSERT_EQ(testing::RunCli("corrupt --quiet --markers=" + clean_ + " --out=" + damaged_ +
                              " --gaps=4 --gap_min=8 --gap_max=20 --cluster_gaps=0 --swaps=0 --noisy_markers=0", &output),
              0) << output;
  }
  std::string Take() const {
    return "--skeleton=" + demo_ + " --skeleton_units=cm --markerset=" + set_ + " --markers=" + damaged_;
  }
  std::string demo_, clean_, damaged_, set_;
};

TEST_F(ViewCli, BadInputsGiveOneLineAndNoPage) {
  MOCAPSOLVE_NEED_VIEWER_RUNTIME();
  const std::string page = testing::TempPath("bad.html");
  const std::string missing = testing::TempPath("missing.c3d");
  const std::string not_json = testing::TempPath("not.json");
  FILE* file = std::fopen(not_json.c_str(), "w");
  std::fputs("{\"detected\": [], \"filled\": [{\"marker\": \"NOPE\", \"first_frame\": 1, \"last_frame\": 2}]}", file);
  std::fclose(file);
  const std::string no_bin = testing::TempPath("no_bin.gltf");  // Its buffer's file is not there.
  testing::WriteTextFile(no_bin, "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"byteLength\": 12, "
                                 "\"uri\": \"missing.bin\"}]}");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--character=" + no_bin + " --out=" + page, "missing.bin"},
      {"--markers=" + clean_, "--out=PAGE.html is required"},
      {"--markers=" + clean_ + " --out=" + testing::TempPath("page.txt"), "expected an .html page"},
      {"--out=" + page, "nothing to show"},
      {"--markers=" + missing + " --out=" + page, "missing.c3d"},
      {"--markers=" + clean_ + " --repair_report=" + not_json + " --out=" + page, "'NOPE' is not a marker"},
      {"--markers=" + clean_ + " --character=" + demo_ + " --out=" + page, "takes .glb or .gltf files"},
      {"--motion=" + demo_ + " --compare=" + clean_ + " --out=" + page, "a marker file needs --markers"},
      {"--markers=" + clean_ + " --up=w --out=" + page, "--up: unknown 'w' (auto, x, y, z)"},
      {"--markers=" + clean_ + " --out=" + clean_, "expected an .html page"},
  };
  for (const auto& [arguments, message] : cases) {
    std::string output;
    EXPECT_EQ(testing::RunCli("view " + arguments, &output), 1) << arguments;
    EXPECT_THAT(output, HasSubstr(message)) << arguments;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
    EXPECT_FALSE(testing::FileExists(page)) << arguments;
  }
  // --view of another command: checked before any work.
  std::string output;
  EXPECT_EQ(testing::RunCli("solve --quiet " + Take() + " --out=" + testing::TempPath("o.bvh") + " --view=" +
                            testing::TempPath("v.svg"), &output), 1);
  EXPECT_THAT(output, HasSubstr("expected an .html page"));
}

TEST_F(ViewCli, MissingRuntimeSaysHowToInstallIt) {
  setenv("MOCAPSOLVE_VIEWER_TOOLS", testing::TempPath("no_tools").c_str(), 1);
  std::string output;
  const std::string page = testing::TempPath("page.html");
  EXPECT_EQ(testing::RunCli("view --markers=" + clean_ + " --out=" + page, &output), 1);
  unsetenv("MOCAPSOLVE_VIEWER_TOOLS");
  EXPECT_THAT(output, HasSubstr("scripts/viewer_tools.sh"));
  EXPECT_FALSE(testing::FileExists(page));
}

TEST_F(ViewCli, PagesDrawInTheBrowser) {
  MOCAPSOLVE_NEED_VIEWER_RUNTIME();
  const std::string repaired = testing::TempPath("repaired.c3d"), report = testing::TempPath("repair.json");
  const std::string repair_page = testing::TempPath("repair.html");
  std::string output;
  ASSERT_EQ(testing::RunCli("repair --quiet " + Take() + " --out_markers=" + repaired + " --report=" + report +
                            " --view=" + repair_page, &output), 0) << output;
  const Repaired first = FirstRepaired(report);
  ASSERT_GE(first.frame, 0) << testing::ReadTextFile(report);

  // The same repair through `view`, with the file's markers in their own world, the
  // clip as the motion and the damaged take ghosted.
  const std::string view_page = testing::TempPath("view.html");
  ASSERT_EQ(testing::RunCli("view --quiet --markers=" + repaired + " --repair_report=" + report + " --motion=" + demo_ +
                            " --skeleton_units=cm --compare=" + damaged_ + " --out=" + view_page, &output), 0)
      << output;
  // A solve's page (markers mapped onto the skeleton, residual curve) and a motion alone.
  const std::string solve_page = testing::TempPath("solve.html");
  ASSERT_EQ(testing::RunCli("solve --quiet " + Take() + " --out=" + testing::TempPath("solved.bvh") + " --view=" +
                            solve_page, &output), 0) << output;
  // The take mapped onto its skeleton (--skeleton is the subject's; the BVH motion carries
  // its own), with the solve's residual and the repaired take ghosted.
  const std::string take_page = testing::TempPath("take.html");
  ASSERT_EQ(testing::RunCli("view --quiet " + Take() + " --motion=" + testing::TempPath("solved.bvh") +
                            " --compare=" + repaired + " --out=" + take_page, &output), 0) << output;
  const std::string motion_page = testing::TempPath("motion.html");
  ASSERT_EQ(testing::RunCli("view --quiet --motion=" + demo_ + " --out=" + motion_page, &output), 0) << output;

  const std::string repaired_check = "{\"label\": \"" + first.label + "\", \"frame\": " + std::to_string(first.frame) +
                                     ", \"state\": \"" + first.state + "\"}";
  MOCAPSOLVE_CHECK_IN_BROWSER("{\"pages\": [\n"
                              "{\"path\": \"" + repair_page + "\", \"moving\": [0, 60], \"repaired\": " + repaired_check + "},\n"
                              "{\"path\": \"" + view_page + "\", \"moving\": [5, 70], \"repaired\": " + repaired_check + "},\n"
                              "{\"path\": \"" + solve_page + "\", \"moving\": [0, 45]},\n"
                              "{\"path\": \"" + take_page + "\", \"moving\": [0, 45]},\n"
                              "{\"path\": \"" + motion_page + "\", \"moving\": [10, 80]}]}\n");
}

// A stand-in for the three.js runtime (what the page embeds does not matter here), so the
// figures `view` prints can be tested without scripts/viewer_tools.sh. Unset on exit.
class StubRuntime {
 public:
  StubRuntime() {
    const std::string dir = testing::TempPath("stub_tools");
    std::filesystem::create_directories(dir);
    testing::WriteTextFile(dir + "/three.bundle.js", "// stub\n");
    setenv("MOCAPSOLVE_VIEWER_TOOLS", dir.c_str(), 1);
  }
  ~StubRuntime() { unsetenv("MOCAPSOLVE_VIEWER_TOOLS"); }
};

// The "marker residual RMS X mm" of a `view` run's summary line, or -1.
double ViewResidualMm(const std::string& output) {
  const std::string key = "marker residual RMS ";
  const size_t at = output.find(key);
  return at == std::string::npos ? -1.0 : std::atof(output.c_str() + at + key.size());
}

// The per-frame solve's RMS marker residual (mm) from its --report.
double SolveResidualMm(const std::string& report_path) {
  JsonNode root;
  if (!ReadJsonFile(report_path, &root).ok()) return -1.0;
  const JsonNode* per_frame = root.Find("per_frame");
  const JsonNode* rms = per_frame != nullptr ? per_frame->Find("rms_marker_residual") : nullptr;
  return rms != nullptr ? rms->number : -1.0;
}

// `view --motion=solved.bvh` over an ASF skeleton (whose rest rotations the BVH folds into
// its angles) draws the motion the solve computed: the residual it shows is the solve's.
TEST(ViewSubjectMotion, ResidualOfASolvedBvhOverAnAsfIsTheSolves) {
  const std::string dir = testing::SourcePath("tests/data/good");
  const std::string asf = dir + "/small.asf", amc = dir + "/small.amc";
  const std::string set = testing::TempPath("small_set.json"), c3d = testing::TempPath("small.c3d");
  const std::string solved = testing::TempPath("small_solved.bvh"), report = testing::TempPath("small_solve.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("markers --quiet --motion=" + amc + " --skeleton=" + asf + " --markerset=auto:3 "
                            "--write_markerset=" + set + " --out=" + c3d, &output), 0) << output;
  const std::string model = " --skeleton=" + asf + " --markerset=" + set + " --markers=" + c3d;
  ASSERT_EQ(testing::RunCli("solve --quiet --solver=dls" + model + " --out=" + solved + " --report=" + report, &output),
            0) << output;
  const double solve_mm = SolveResidualMm(report);
  ASSERT_GE(solve_mm, 0.0) << testing::ReadTextFile(report);
  StubRuntime stub;
  ASSERT_EQ(testing::RunCli("view" + model + " --motion=" + solved + " --out=" + testing::TempPath("small.html"),
                            &output), 0) << output;
  EXPECT_NEAR(ViewResidualMm(output), solve_mm, 1e-3 + 1e-3 * solve_mm) << output;
  // A motion of another skeleton: one line naming the motion file and the joint.
  const std::string demo = testing::TempPath("small_other.bvh");
  ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo + " --frames=3 --fps=30", &output), 0) << output;
  EXPECT_EQ(testing::RunCli("view" + model + " --motion=" + demo + " --out=" + testing::TempPath("other.html"), &output),
            1);
  EXPECT_THAT(output, HasSubstr(demo + ": its skeleton has"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
}

// The README's recipe: calibrate 02_01 into a subject, solve, view the solve with the
// subject: the residual is the solve's (it was 340 mm, the skeleton on its side).
TEST(ViewRealData, ReadmeRecipeResidualIsTheSolves) {
  MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
  MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
  MOCAPSOLVE_DATA_FILE(c3d, "c3d/02_01.c3d");
  const std::string subject = testing::TempPath("recipe_S02.json"), solved = testing::TempPath("recipe_s.bvh");
  const std::string report = testing::TempPath("recipe_solve.json");
  std::string output;
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + amc + " --skeleton=" + asf + " --markers=" + c3d +
                            " --axes=y,z,x --out_subject=" + subject, &output), 0) << output;
  ASSERT_EQ(testing::RunCli("solve --quiet --subject=" + subject + " --markers=" + c3d + " --max_frames=60 --out=" +
                            solved + " --report=" + report, &output), 0) << output;
  const double solve_mm = SolveResidualMm(report);
  ASSERT_GT(solve_mm, 0.0);
  EXPECT_LT(solve_mm, 20.0);
  StubRuntime stub;
  ASSERT_EQ(testing::RunCli("view --subject=" + subject + " --markers=" + c3d + " --motion=" + solved + " --out=" +
                            testing::TempPath("recipe.html"), &output), 0) << output;
  EXPECT_NEAR(ViewResidualMm(output), solve_mm, 0.01 * solve_mm) << output;
}

// Real data: CMU 02_01 through the pipeline onto Xbot; its view.html plays the character
// beside the solve.
TEST(ViewRealData, PipelinePageWithCharacter) {
  MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
  MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
  MOCAPSOLVE_DATA_FILE(c3d, "c3d/02_01.c3d");
  MOCAPSOLVE_DATA_FILE(xbot, "gltf/Xbot.glb");
  MOCAPSOLVE_NEED_VIEWER_RUNTIME();
  const std::string subject = testing::TempPath("S02.json"), dir = testing::TempPath("02_01");
  std::string output;
  ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + amc + " --skeleton=" + asf + " --markers=" + c3d +
                            " --axes=y,z,x --out=" + testing::TempPath("02.json") + " --out_subject=" + subject,
                            &output), 0) << output;
  // The page is the point here, not the gate: Xbot's feet go 3.3 cm under the floor on this
  // take (BENCHMARKS.md, retarget quality), so the penetration check is off.
  ASSERT_EQ(testing::RunCli("pipeline --quiet --subject=" + subject + " --markers=" + c3d + " --character=" + xbot +
                            " --out_dir=" + dir + " --gate_penetration_cm=0", &output), 0) << output;
  ASSERT_TRUE(testing::FileExists(dir + "/view.html"));
  EXPECT_THAT(testing::ReadTextFile(dir + "/report.json"), HasSubstr("\"view\": \"view.html\""));
  // The delivered character alone: its last frame is the clip's last pose, not its first.
  const std::string characters = testing::TempPath("characters.html");
  ASSERT_EQ(testing::RunCli("view --quiet --character=" + dir + "/Xbot.glb --out=" + characters, &output), 0) << output;
  MOCAPSOLVE_CHECK_IN_BROWSER("{\"pages\": [{\"path\": \"" + dir + "/view.html\", \"moving\": [0, 200], "
                              "\"min_share\": 0.015},\n"
                              "{\"path\": \"" + characters + "\", \"moving\": [0, 342]}]}\n");
}

// --view of retarget (the source skeleton beside the target character) and of propagate
// (the edited clip over the original, the falloff on the timeline).
TEST(ViewRealData, RetargetAndPropagatePages) {
  MOCAPSOLVE_DATA_FILE(source, "gltf/CesiumMan.glb");
  MOCAPSOLVE_DATA_FILE(target, "gltf/RiggedFigure.glb");
  MOCAPSOLVE_DATA_FILE(walk, "bvh/16_15.bvh");
  MOCAPSOLVE_NEED_VIEWER_RUNTIME();
  const std::string retarget_page = testing::TempPath("retarget.html"), propagate_page = testing::TempPath("edit.html");
  std::string output;
  ASSERT_EQ(testing::RunCli("retarget --quiet --source=" + source + " --target=" + target + " --out=" +
                            testing::TempPath("r.glb") + " --iterations=5 --max_frames=24 --view=" + retarget_page,
                            &output), 0) << output;
  const std::string edit = testing::TempPath("hips.json");
  FILE* file = std::fopen(edit.c_str(), "w");
  std::fputs("{\"frame\": 200, \"joints\": {\"root\": {\"rotation_offset_deg\": [10, 0, 0]}}}", file);
  std::fclose(file);
  ASSERT_EQ(testing::RunCli("propagate --motion=" + walk + " --skeleton_units=cm --edit=" + edit +
                            " --method=spline --out=" + testing::TempPath("e.bvh") + " --view=" + propagate_page, &output),
            0) << output;
  MOCAPSOLVE_CHECK_IN_BROWSER("{\"pages\": [{\"path\": \"" + retarget_page + "\", \"moving\": [0, 20]},\n"
                              "{\"path\": \"" + propagate_page + "\", \"moving\": [150, 250]}]}\n");
}

// .gltf characters, with their buffers and texture in files beside them or as data: URIs,
// are embedded as one .glb each: the page, elsewhere, needs nothing beside it.
TEST(ViewRealData, GltfCharacters) {
  MOCAPSOLVE_DATA_FILE(cesium, "gltf/CesiumMan.glb");
  MOCAPSOLVE_NEED_VIEWER_RUNTIME();
  const std::string files = testing::TempPath("files/CesiumMan.gltf"), data = testing::TempPath("data/CesiumMan.gltf");
  for (const std::string& path : {files, data}) std::filesystem::create_directories(path.substr(0, path.rfind('/')));
  testing::WriteGltfVariant(cesium, files, testing::GltfLayout::kSeparateFiles);
  testing::WriteGltfVariant(cesium, data, testing::GltfLayout::kDataUris);
  const std::string page = testing::TempPath("gltf.html");
  std::string output;
  ASSERT_EQ(testing::RunCli("view --quiet --character=" + files + "," + data + " --out=" + page, &output), 0) << output;
  const std::string html = testing::ReadTextFile(page);
  EXPECT_EQ(html.find("CesiumMan.bin"), std::string::npos);
  EXPECT_EQ(html.find("CesiumMan_image0.jpg"), std::string::npos);
  MOCAPSOLVE_CHECK_IN_BROWSER("{\"pages\": [{\"path\": \"" + page + "\", \"moving\": [0, 20]}]}\n");
}

}  // namespace
}  // namespace mocapsolve
