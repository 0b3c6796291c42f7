// `mocapsolve batch` on small takes the project makes (the demo walk, 40 frames, markers
// synthesized from it, a subject calibrated on it): a resumable batch, its faults (a
// truncated file, a subject that does not fit, a crashing worker, a timeout, an
// unwritable folder, a killed batch) and bad manifests.
#include <dirent.h>
#include <sys/stat.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <cstdlib>
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


std::vector<std::string> FolderFiles(const std::string& folder) {
  std::vector<std::string> names;
  DIR* dir = ::opendir(folder.c_str());
  if (dir == nullptr) return names;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (name != "." && name != "..") names.push_back(name);
  }
  ::closedir(dir);
  std::sort(names.begin(), names.end());
  return names;
}

// summary.json's takes by name: status, ran, exit, error.
struct Row {
  std::string status, exit, error;
  bool ran = false;
  int frames = 0;
};
std::map<std::string, Row> Summary(const std::string& dir) {
  std::map<std::string, Row> rows;
  JsonNode root;
  const Status status = ReadJsonFile(dir + "/summary.json", &root);
  EXPECT_TRUE(status.ok()) << status.message();
  if (!status.ok()) return rows;
  for (const JsonNode& take : root.Find("takes")->items) {
    Row& row = rows[take.Find("take")->string];
    row.status = take.Find("status")->string;
    row.exit = take.Find("exit")->string;
    row.error = take.Find("error")->string;
    row.ran = take.Find("ran")->boolean;
    row.frames = static_cast<int>(take.Find("frames")->number);
  }
  return rows;
}

class BatchCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::TempPath("takes");
    ASSERT_EQ(std::system(("mkdir -p " + dir_).c_str()), 0);
    const std::string demo = dir_ + "/walk.bvh", markers = dir_ + "/walk.c3d";
    std::string output;
    ASSERT_EQ(testing::RunCli("generate --demo_out=" + demo + " --frames=40 --fps=30", &output), 0) << output;
    ASSERT_EQ(testing::RunCli("markers --motion=" + demo + " --skeleton_units=cm --markerset=auto:3 --noise_mm=0.5 "
                              "--seed=3 --out=" + markers, &output), 0) << output;
    ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + demo + " --skeleton_units=cm --markers=" + markers +
                              " --attach=auto --out=" + dir_ + "/calibrated.json --out_subject=" + dir_ + "/S.json",
                              &output), 0) << output;
    for (const char* name : {"t1", "t2", "t3", "t4"}) {
      ASSERT_EQ(std::system(("cp " + markers + " " + dir_ + "/" + name + ".c3d").c_str()), 0);
    }
  }
  std::string Manifest(const std::string& takes) {
    const std::string path = dir_ + "/M.json";
    testing::WriteTextFile(path, "{\"defaults\": {\"subject\": \"S.json\"},\n \"takes\": [" + takes + "]}\n");
    return path;
  }
  std::string dir_;
};

TEST_F(BatchCli, RunsResumesRedoesChangedAndForced) {
  const std::string out = testing::TempPath("out");
  const std::string manifest = dir_ + "/M.json";
  std::string output;
  // The glob form writes the manifest; then the manifest form runs it.
  ASSERT_EQ(testing::RunCli("batch --markers_glob='" + dir_ + "/t*.c3d' --subject=" + dir_ + "/S.json "
                            "--write_manifest=" + manifest, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("4 takes"));
  const std::string run = "batch --quiet --manifest=" + manifest + " --out_dir=" + out + " --jobs=2";
  ASSERT_EQ(testing::RunCli(run, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("4 done, 0 failed (4 ran, 0 skipped"));
  auto rows = Summary(out);
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& [name, row] : rows) {
    EXPECT_EQ(row.status, "done") << name << ": " << row.error;
    EXPECT_EQ(row.frames, 40) << name;
    EXPECT_TRUE(testing::FileExists(out + "/" + name + "/solved.bvh")) << name;
    EXPECT_TRUE(testing::FileExists(out + "/" + name + "/record.json")) << name;
  }
  EXPECT_THAT(testing::ReadTextFile(out + "/summary.csv"), HasSubstr("t3,done,1,0,0,,40,"));
  // Nothing to do.
  ASSERT_EQ(testing::RunCli(run, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("4 done, 0 failed (0 ran, 4 skipped"));
  // One input changed (a byte after the C3D's data): only that take again.
  {
    std::FILE* file = std::fopen((dir_ + "/t2.c3d").c_str(), "a");
    std::fputc('\n', file);
    std::fclose(file);
  }
  ASSERT_EQ(testing::RunCli(run, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("(1 ran, 3 skipped"));
  rows = Summary(out);
  EXPECT_TRUE(rows["t2"].ran);
  EXPECT_FALSE(rows["t1"].ran);
  // An option of one take changed: only that take.
  {
    std::string text = testing::ReadTextFile(manifest);
    const size_t at = text.find("\"markers\": \"" + dir_ + "/t4.c3d\"");
    ASSERT_NE(at, std::string::npos) << text;
    text.insert(at, "\"filter_levels\": 1, ");
    testing::WriteTextFile(manifest, text);
  }
  ASSERT_EQ(testing::RunCli(run, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("(1 ran, 3 skipped"));
  EXPECT_TRUE(Summary(out)["t4"].ran);
  // A lost output: that take again.
  ASSERT_EQ(std::remove((out + "/t1/solved.bvh").c_str()), 0);
  ASSERT_EQ(testing::RunCli(run, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("(1 ran, 3 skipped"));
  // A file an earlier run left (older than the take's run) is not listed as its output.
  testing::WriteTextFile(out + "/t3/stale.glb", "old");
  ASSERT_EQ(std::system(("touch -d @1000000000 " + out + "/t3/stale.glb").c_str()), 0);
  ASSERT_EQ(testing::RunCli(run + " --force", &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("(4 ran, 0 skipped"));
  const std::string record = testing::ReadTextFile(out + "/t3/record.json");
  std::string runtime;  // view.html when the viewer's runtime is installed.
  EXPECT_THAT(record, HasSubstr(FindViewerRuntime(&runtime).ok()
                                    ? "\"outputs\": [\"repaired.c3d\", \"report.json\", \"solved.bvh\", \"view.html\"]"
                                    : "\"outputs\": [\"repaired.c3d\", \"report.json\", \"solved.bvh\"]"));
}

// --formats goes to every take's worker (over the manifest's defaults; a take's own value
// wins), and into the written manifest; a bad list is the batch's one-line error.
TEST_F(BatchCli, FormatsReachEveryTake) {
  const std::string character = dir_ + "/figure.gltf";
  testing::WriteTestCharacter(character, 45.0);
  const std::string out = testing::TempPath("formats_out");
  const std::string manifest = Manifest(
      "{\"markers\": \"t1.c3d\", \"characters\": [\"figure.gltf\"], \"gate_limb_vertices\": 0},\n"
      " {\"markers\": \"t2.c3d\", \"characters\": [\"figure.gltf\"], \"formats\": \"bvh\", "
      "\"gate_limb_vertices\": 0}");  // The test figure: one vertex per joint.
  std::string output;
  ASSERT_EQ(testing::RunCli("batch --quiet --jobs=2 --manifest=" + manifest + " --out_dir=" + out +
                            " --formats=glb,fbx", &output), 0) << output;
  EXPECT_TRUE(testing::FileExists(out + "/t1/figure.gltf"));
  EXPECT_TRUE(testing::FileExists(out + "/t1/figure.fbx"));
  EXPECT_FALSE(testing::FileExists(out + "/t1/figure.bvh"));
  EXPECT_TRUE(testing::FileExists(out + "/t2/figure.bvh"));
  EXPECT_FALSE(testing::FileExists(out + "/t2/figure.fbx"));
  EXPECT_THAT(testing::ReadTextFile(out + "/t1/record.json"), HasSubstr("figure.fbx"));
  // The same again: nothing to do; without --formats the options changed: both again.
  ASSERT_EQ(testing::RunCli("batch --quiet --jobs=2 --manifest=" + manifest + " --out_dir=" + out +
                            " --formats=glb,fbx", &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("(0 ran, 2 skipped"));
  ASSERT_EQ(testing::RunCli("batch --quiet --jobs=2 --manifest=" + manifest + " --out_dir=" + out, &output), 0)
      << output;
  EXPECT_THAT(output, HasSubstr("(1 ran, 1 skipped"));
  EXPECT_FALSE(testing::FileExists(out + "/t1/figure.fbx"));
  // The glob form's written manifest keeps it.
  const std::string written = dir_ + "/W.json";
  ASSERT_EQ(testing::RunCli("batch --markers_glob='" + dir_ + "/t*.c3d' --subject=" + dir_ + "/S.json "
                            "--formats=fbx --write_manifest=" + written, &output), 0) << output;
  EXPECT_THAT(testing::ReadTextFile(written), HasSubstr("\"formats\": \"fbx\""));
  const std::string none = testing::TempPath("formats_none");
  EXPECT_EQ(testing::RunCli("batch --manifest=" + manifest + " --out_dir=" + none + " --formats=glb,obj", &output), 1);
  EXPECT_THAT(output, HasSubstr("--formats: unknown 'obj' (glb, fbx, bvh)"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  EXPECT_FALSE(testing::FileExists(none));
}

TEST_F(BatchCli, FaultsFailOnlyTheirTake) {
  // A truncated C3D; a marker file whose labels the subject does not have; a worker that
  // aborts; an output folder that is a file.
  {
    const std::string text = testing::ReadTextFile(dir_ + "/t1.c3d");
    testing::WriteTextFile(dir_ + "/truncated.c3d", text.substr(0, 3000));
  }
  testing::WriteTextFile(dir_ + "/other.trc",
            "PathFileType\t4\t(X/Y/Z)\tother.trc\n"
            "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames\n"
            "30\t30\t2\t1\tmm\t30\t1\t2\n"
            "Frame#\tTime\tNOPE\t\t\n"
            "\t\tX1\tY1\tZ1\n"
            "1\t0\t1\t2\t3\n"
            "2\t0.0333\t1\t2\t3\n");
  const std::string out = testing::TempPath("faults");
  ASSERT_EQ(std::system(("mkdir -p " + out).c_str()), 0);
  testing::WriteTextFile(out + "/unwritable", "a file where the take's folder should be");
  const std::string manifest = Manifest(
      "{\"name\": \"ok\", \"markers\": \"t1.c3d\"}, {\"name\": \"truncated\", \"markers\": \"truncated.c3d\"},\n"
      "{\"name\": \"mismatch\", \"markers\": \"other.trc\"}, {\"name\": \"crash\", \"markers\": \"t2.c3d\"},\n"
      "{\"name\": \"unwritable\", \"markers\": \"t3.c3d\"}, {\"name\": \"gate\", \"markers\": \"t4.c3d\", "
      "\"gate_repaired_rms_mm\": 0.0001}, {\"name\": \"killed\", \"markers\": \"t3.c3d\"}");
  std::string output;
  ::setenv("MOCAPSOLVE_TEST_CRASH_TAKE", "crash,killed:KILL", 1);
  const int code = testing::RunCli("batch --quiet --manifest=" + manifest + " --out_dir=" + out + " --jobs=2", &output);
  ::unsetenv("MOCAPSOLVE_TEST_CRASH_TAKE");
  EXPECT_EQ(code, 2) << output;
  auto rows = Summary(out);
  ASSERT_EQ(rows.size(), 7u);
  EXPECT_EQ(rows["ok"].status, "done");
  EXPECT_EQ(rows["truncated"].exit, "1");
  EXPECT_THAT(rows["truncated"].error, HasSubstr("truncated.c3d"));
  EXPECT_EQ(rows["mismatch"].exit, "1");
  EXPECT_THAT(rows["mismatch"].error, HasSubstr("other.trc"));
  EXPECT_EQ(rows["crash"].exit, "SIGABRT");
  EXPECT_EQ(rows["killed"].exit, "SIGKILL");
  EXPECT_EQ(rows["unwritable"].exit, "1");
  EXPECT_THAT(rows["unwritable"].error, HasSubstr("not a folder"));
  EXPECT_EQ(rows["gate"].exit, "3");
  EXPECT_THAT(rows["gate"].error, HasSubstr("quality gate failed"));
  EXPECT_EQ(rows["gate"].status, "gate_failed");  // It ran; its outputs are kept.
  EXPECT_THAT(output, HasSubstr("; 1 failed at the quality gate"));
  for (const auto& [name, row] : rows) {
    if (name != "ok" && name != "gate") {
      EXPECT_EQ(row.status, "failed") << name;
    }
    EXPECT_EQ(row.error.find('\n'), std::string::npos) << name;
  }
  // Nothing partial: a failed take's folder holds its record alone (a failed gate keeps
  // its outputs, as the pipeline does).
  for (const char* name : {"truncated", "mismatch", "crash", "killed"}) {
    EXPECT_EQ(FolderFiles(out + "/" + name), std::vector<std::string>{"record.json"}) << name;
  }
  // view.html when the viewer's runtime is installed (scripts/viewer_tools.sh).
  std::string runtime;
  std::vector<std::string> ok_files = {"record.json", "repaired.c3d", "report.json", "solved.bvh"};
  if (FindViewerRuntime(&runtime).ok()) ok_files.push_back("view.html");
  EXPECT_EQ(FolderFiles(out + "/ok"), ok_files);
  EXPECT_EQ(FolderFiles(out), (std::vector<std::string>{"crash", "gate", "killed", "mismatch", "ok", "summary.csv",
                                                         "summary.html",
                                                         "summary.json", "truncated", "unwritable"}));
  // Failed takes stay failed on a re-run, and are redone with --retry_failed.
  EXPECT_EQ(testing::RunCli("batch --quiet --manifest=" + manifest + " --out_dir=" + out, &output), 2) << output;
  EXPECT_THAT(output, HasSubstr("1 done, 6 failed (1 ran, 6 skipped"));  // unwritable has no record.
  EXPECT_EQ(testing::RunCli("batch --quiet --retry_failed --manifest=" + manifest + " --out_dir=" + out, &output),
            2) << output;
  rows = Summary(out);
  EXPECT_EQ(rows["crash"].status, "done");
  EXPECT_EQ(rows["killed"].status, "done");
  EXPECT_EQ(rows["truncated"].status, "failed");
  // A take over its memory limit fails alone, with nothing partial.
  const std::string limited = testing::TempPath("memory_limit");
  EXPECT_EQ(testing::RunCli("batch --quiet --take_memory_mb=16 --manifest=" + manifest + " --out_dir=" + limited,
                            &output), 2) << output;
  rows = Summary(limited);
  EXPECT_NE(rows["ok"].exit, "0");
  EXPECT_EQ(rows["ok"].status, "failed");
  EXPECT_EQ(FolderFiles(limited + "/ok"), std::vector<std::string>{"record.json"});
}

TEST_F(BatchCli, TimeoutAndKilledBatch) {
  const std::string manifest = Manifest("{\"markers\": \"t1.c3d\"}, {\"markers\": \"t2.c3d\"}, "
                                        "{\"markers\": \"t3.c3d\"}, {\"markers\": \"t4.c3d\"}");
  const std::string out = testing::TempPath("timeout");
  std::string output;
  EXPECT_EQ(testing::RunCli("batch --quiet --take_timeout=0.01 --manifest=" + manifest + " --out_dir=" + out,
                            &output), 2) << output;
  for (const auto& [name, row] : Summary(out)) {
    EXPECT_EQ(row.exit, "timeout") << name;
    EXPECT_THAT(row.error, HasSubstr("timed out after 0.01 s"));
    EXPECT_EQ(FolderFiles(out + "/" + name), std::vector<std::string>{"record.json"}) << name;
  }
  // A batch killed (SIGKILL) while takes run: every take folder has a record with its
  // outputs, or no record; no temporary files; the next run finishes the rest.
  const std::string killed = testing::TempPath("killed");
  const std::string command = testing::CliPath() + " batch --quiet --jobs=2 --manifest=" + manifest +
                              " --out_dir=" + killed + " >/dev/null 2>&1 & pid=$!; sleep 0.2; kill -9 $pid; wait $pid";
  std::system(command.c_str());
  ::usleep(200000);  // The workers die with the batch (PR_SET_PDEATHSIG).
  // A recorded take has its record, repaired.c3d, report.json, solved.bvh, and view.html
  // when the viewer's runtime is installed.
  std::string runtime;
  const size_t take_files = FindViewerRuntime(&runtime).ok() ? 5u : 4u;
  int recorded = 0;
  for (const std::string& take : FolderFiles(killed)) {
    const std::vector<std::string> files = FolderFiles(killed + "/" + take);
    for (const std::string& file : files) EXPECT_EQ(file.find("tmp"), std::string::npos) << take << "/" << file;
    if (std::find(files.begin(), files.end(), "record.json") != files.end()) {
      ++recorded;
      EXPECT_EQ(files.size(), take_files) << take;
    }
  }
  // (On a fast machine the batch may have finished before the kill: then every take is
  // recorded and the next run skips them all; the checks above and below hold either way.)
  ASSERT_EQ(testing::RunCli("batch --quiet --jobs=2 --manifest=" + manifest + " --out_dir=" + killed, &output), 0)
      << output;
  EXPECT_THAT(output, HasSubstr("(" + std::to_string(4 - recorded) + " ran, " + std::to_string(recorded) + " skipped"));
}

TEST_F(BatchCli, ShardsAndMerge) {
  const std::string manifest = Manifest("{\"markers\": \"t1.c3d\"}, {\"markers\": \"t2.c3d\"}, "
                                        "{\"markers\": \"t3.c3d\"}");
  const std::string out = testing::TempPath("shards");
  std::string output;
  ASSERT_EQ(testing::RunCli("batch --quiet --shard=1/2 --manifest=" + manifest + " --out_dir=" + out, &output), 0)
      << output;
  EXPECT_THAT(output, HasSubstr("1 done, 0 failed"));
  EXPECT_TRUE(testing::FileExists(out + "/summary.shard1of2.json"));
  EXPECT_TRUE(testing::FileExists(out + "/t2/record.json"));
  EXPECT_FALSE(testing::FileExists(out + "/t1"));
  // Merged before shard 0 ran: t1 and t3 missing.
  EXPECT_EQ(testing::RunCli("batch --merge --manifest=" + manifest + " --out_dir=" + out, &output), 2) << output;
  EXPECT_EQ(Summary(out)["t1"].status, "missing");
  // The Slurm job array's variables pick the shard.
  ::setenv("SLURM_ARRAY_TASK_ID", "0", 1);
  ::setenv("SLURM_ARRAY_TASK_COUNT", "2", 1);
  const int code = testing::RunCli("batch --quiet --manifest=" + manifest + " --out_dir=" + out, &output);
  ::unsetenv("SLURM_ARRAY_TASK_ID");
  ::unsetenv("SLURM_ARRAY_TASK_COUNT");
  ASSERT_EQ(code, 0) << output;
  EXPECT_THAT(output, HasSubstr("2 done, 0 failed"));
  EXPECT_TRUE(testing::FileExists(out + "/summary.shard0of2.json"));
  ASSERT_EQ(testing::RunCli("batch --merge --out_dir=" + out, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("merged 3 take records: 3 done, 0 failed"));
  const auto rows = Summary(out);
  ASSERT_EQ(rows.size(), 3u);
  for (const auto& [name, row] : rows) EXPECT_EQ(row.status, "done") << name;
  EXPECT_EQ(testing::RunCli("batch --shard=2/2 --manifest=" + manifest + " --out_dir=" + out, &output), 1);
  EXPECT_THAT(output, HasSubstr("--shard=2/2"));
}

// Every output is checked against every input by file identity before anything is written:
// a subject named like the summary, a --write_manifest onto a marker file (directly, by a
// symlink, by a hard link), a take folder holding an input, a manifest written where a
// take's folder goes. Each: one line, exit 1, the input unchanged, nothing written.
TEST_F(BatchCli, OutputsNeverReplaceInputs) {
  const std::string out = testing::TempPath("guard");
  ASSERT_EQ(std::system(("mkdir -p " + out + "/t1 " + out + "/.batch-work && cp " + dir_ + "/t4.c3d " + out +
                         "/.batch-work/w.c3d && cp " + dir_ + "/S.json " + out + "/summary.csv && ln -s " +
                         dir_ + "/S.json " + dir_ + "/link.json && ln " + dir_ + "/t2.c3d " + out +
                         "/hard.c3d && cp " + dir_ + "/t3.c3d " + out + "/t1/inside.c3d").c_str()), 0);
  const std::string subject_text = testing::ReadTextFile(out + "/summary.csv");
  const std::string markers_text = testing::ReadTextFile(dir_ + "/t1.c3d");
  const std::string glob = "batch --markers_glob='" + dir_ + "/t*.c3d' ";
  struct Case {
    std::string arguments, expected;
  };
  const std::vector<Case> cases = {
      {glob + "--subject=" + out + "/summary.csv --out_dir=" + out,
       "the summary " + out + "/summary.csv is the subject file of take 't1' (refusing to overwrite an input)"},
      {glob + "--subject=" + dir_ + "/S.json --write_manifest=" + dir_ + "/t1.c3d",
       "--write_manifest=" + dir_ + "/t1.c3d is the markers file of take 't1'"},
      {glob + "--subject=" + dir_ + "/S.json --write_manifest=" + dir_ + "/link.json --out_dir=" + out,
       "--write_manifest=" + dir_ + "/link.json is the subject file of take 't1'"},
      {glob + "--subject=" + dir_ + "/S.json --write_manifest=" + out + "/hard.c3d",
       "--write_manifest=" + out + "/hard.c3d is the markers file of take 't2'"},
      {"batch --markers_glob='" + out + "/.batch-work/*.c3d' --subject=" + dir_ + "/S.json --out_dir=" + out,
       "the work folder " + out + "/.batch-work holds the markers file of take 'w'"},
      {glob + "--subject=" + dir_ + "/S.json --character=" + out + "/t1/inside.c3d --out_dir=" + out,
       "the folder of take 't1' (" + out + "/t1) holds the character file of take 't1'"},
      {glob + "--subject=" + dir_ + "/S.json --write_manifest=" + out + "/t3 --out_dir=" + out,
       "the folder of take 't3' (" + out + "/t3) is also --write_manifest=" + out + "/t3"},
  };
  const std::vector<std::string> before = FolderFiles(out);
  for (const Case& c : cases) {
    std::string output;
    EXPECT_EQ(testing::RunCli(c.arguments, &output), 1) << c.arguments << "\n" << output;
    EXPECT_THAT(output, HasSubstr(c.expected)) << c.arguments;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
    EXPECT_EQ(FolderFiles(out), before) << c.arguments;
    EXPECT_EQ(FolderFiles(out + "/t1"), std::vector<std::string>{"inside.c3d"});
  }
  EXPECT_EQ(testing::ReadTextFile(out + "/summary.csv"), subject_text);
  EXPECT_EQ(testing::ReadTextFile(dir_ + "/t1.c3d"), markers_text);
  EXPECT_EQ(testing::ReadTextFile(dir_ + "/S.json"), subject_text);
}

// A take whose input is missing, a FIFO (which would block any read) or a folder fails
// alone with its one-line error, before any worker; the others run; exit 2. `info` on a
// FIFO does not block either (every reader opens files the same way).
TEST_F(BatchCli, TakesWithMissingOrIrregularInputsFailAlone) {
  ASSERT_EQ(::mkfifo((dir_ + "/fifo.c3d").c_str(), 0600), 0);
  ASSERT_EQ(std::system(("mkdir -p " + dir_ + "/folder.c3d").c_str()), 0);
  const std::string manifest = Manifest(
      "{\"markers\": \"t1.c3d\"}, {\"markers\": \"missing.c3d\"}, {\"markers\": \"fifo.c3d\"},\n"
      "{\"markers\": \"folder.c3d\"}, {\"name\": \"fifo_subject\", \"markers\": \"t2.c3d\", \"subject\": "
      "\"fifo.c3d\"}");
  const std::string out = testing::TempPath("missing");
  std::string output;
  EXPECT_EQ(testing::RunCli("batch --quiet --take_timeout=60 --manifest=" + manifest + " --out_dir=" + out, &output),
            2) << output;
  auto rows = Summary(out);
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows["t1"].status, "done") << rows["t1"].error;
  EXPECT_EQ(rows["missing"].error, "markers: " + dir_ + "/missing.c3d: cannot open (No such file or directory)");
  EXPECT_EQ(rows["fifo"].error, "markers: " + dir_ + "/fifo.c3d: is not a regular file (a FIFO)");
  EXPECT_EQ(rows["folder"].error, "markers: " + dir_ + "/folder.c3d: is not a regular file (a folder)");
  EXPECT_EQ(rows["fifo_subject"].error, "subject: " + dir_ + "/fifo.c3d: is not a regular file (a FIFO)");
  for (const char* name : {"missing", "fifo", "folder", "fifo_subject"}) {
    EXPECT_EQ(rows[name].status, "failed") << name;
    EXPECT_EQ(rows[name].exit, "1") << name;
    EXPECT_FALSE(testing::FileExists(out + "/" + name)) << name;  // No worker, no folder.
  }
  EXPECT_EQ(testing::RunCli("info " + dir_ + "/fifo.c3d", &output), 1) << output;
  EXPECT_THAT(output, HasSubstr(dir_ + "/fifo.c3d: is not a regular file (a FIFO)"));
}

// Bookkeeping of a batch killed mid-way: the manifest was written at the start, the
// summary lists the takes that ended (the rest pending), the takes' configs sit in the
// out folder's work folder (nothing in TMPDIR), and the next run clears them.
TEST_F(BatchCli, KilledBatchLeavesManifestSummaryAndNoTemporaryFiles) {
  const std::string out = testing::TempPath("bookkeeping");
  const std::string tmp = testing::TempPath("tmpdir");
  const std::string written = dir_ + "/written.json";
  ASSERT_EQ(std::system(("mkdir -p " + tmp).c_str()), 0);
  // Two slow takes after two quick ones; killed once the first summary appears.
  const std::string command =
      "TMPDIR=" + tmp + " " + testing::CliPath() + " batch --quiet --jobs=1 --markers_glob='" + dir_ +
      "/t*.c3d' --subject=" + dir_ + "/S.json --write_manifest=" + written + " --out_dir=" + out +
      " >/dev/null 2>&1 & pid=$!; for i in $(seq 600); do [ -f " + out +
      "/summary.json ] && break; sleep 0.1; done; kill -9 $pid; wait $pid";
  std::system(command.c_str());
  ::usleep(200000);
  EXPECT_TRUE(testing::FileExists(written));
  JsonNode summary;
  ASSERT_TRUE(ReadJsonFile(out + "/summary.json", &summary).ok());
  const int listed = static_cast<int>(summary.Find("takes")->items.size());
  EXPECT_GE(listed, 1);
  EXPECT_EQ(listed + static_cast<int>(summary.Find("pending")->number), 4);
  EXPECT_TRUE(testing::FileExists(out + "/summary.html"));
  EXPECT_EQ(FolderFiles(tmp), std::vector<std::string>{});
  // A stale config from the killed run is cleared by the next, which removes the folder.
  testing::WriteTextFile(out + "/.batch-work/stale.json", "{}");
  std::string output;
  ASSERT_EQ(testing::RunCli("batch --quiet --manifest=" + written + " --out_dir=" + out, &output), 0) << output;
  EXPECT_FALSE(testing::FileExists(out + "/.batch-work"));
  EXPECT_EQ(Summary(out).size(), 4u);
  EXPECT_EQ(Summary(out)["t1"].status, "done");
}

TEST_F(BatchCli, BadManifestsNameFileAndField) {
  const std::string out = testing::TempPath("bad");
  std::string output;
  std::string manifest = Manifest("{\"markers\": \"t1.c3d\", \"filter_level\": 1}");
  EXPECT_EQ(testing::RunCli("batch --manifest=" + manifest + " --out_dir=" + out, &output), 1) << output;
  EXPECT_THAT(output, HasSubstr("M.json:2:"));
  EXPECT_THAT(output, HasSubstr("unknown key 'filter_level'"));
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  // Names that cannot be a folder, or would be the batch's own files: the manifest's error,
  // naming the take (escaped, never cut at a NUL) and the field, not a temporary path.
  const std::vector<std::pair<std::string, std::string>> names = {
      {"a\\u0000b", "takes[1].name: the take name 'a\\x00b'"},
      {"summary.html", "takes[1].name: the take name 'summary.html' is a file the batch writes"},
      {"..", "takes[1].name: the take name '..'"},
      {"x/y", "takes[1].name: the take name 'x/y'"},
      {std::string(300, 'n'), "takes[1].name: the take name '" + std::string(64, 'n') + "...' is 300 bytes long"}};
  for (const auto& [name, expected] : names) {
    manifest = Manifest("{\"name\": \"a\", \"markers\": \"t1.c3d\"}, {\"name\": \"" + name +
                        "\", \"markers\": \"t2.c3d\"}");
    EXPECT_EQ(testing::RunCli("batch --manifest=" + manifest + " --out_dir=" + out, &output), 1) << output;
    EXPECT_THAT(output, HasSubstr(expected));
    EXPECT_THAT(output, HasSubstr("M.json:2:"));
    EXPECT_EQ(output.find(".batch-work"), std::string::npos) << output;  // No config path.
    EXPECT_EQ(output.find("mocapsolve-batch"), std::string::npos) << output;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  }
  EXPECT_EQ(testing::RunCli("batch --manifest=" + dir_ + "/none.json --out_dir=" + out, &output), 1) << output;
  EXPECT_THAT(output, HasSubstr("none.json"));
  struct stat st;
  EXPECT_NE(::stat(out.c_str(), &st), 0);  // Nothing written.
}

}  // namespace
}  // namespace mocapsolve
