// Takes without data, through every command that computes on frames: a motion of 0
// frames, marker files of 0 frames, of every sample missing and of no points (the last
// with 2^24 frames, the most a take may have). A 0-frame take segfaulted `repair` (with
// and without --reference=clip) and `evaluate` (also --method=small_errors); a C3D of 0
// points and 2^31 - 1 frames crashed convert, corrupt and view with std::bad_alloc and
// kept filter running until killed. Each command must now refuse each with exit 1, one
// line naming the file, nothing written, within 5 s; `info` still describes them.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/c3d_reader.h"
#include "io/c3d_writer.h"
#include "io/input_limits.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using ::testing::HasSubstr;

std::string Replaced(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// IN is the empty take, DIR the folder of the good companions, OUT a fresh output folder.
const char* const kMotionCommands[] = {
    "fk --quiet --motion=IN --out=OUT/x.csv",
    "filter --quiet --motion=IN --levels=2 --out=OUT/x.bvh",
    "bands --quiet --motion=IN --weights=1,1 --out=OUT/x.bvh",
    "markers --quiet --motion=IN --markerset=DIR/markerset.json --out=OUT/x.c3d",
    "propagate --quiet --motion=IN --frame=0 --edit=DIR/edit.json --out=OUT/x.bvh",
    "distance --quiet --motion=IN --frame=0 --out=OUT/x.csv",
    "blend --quiet --a=IN --b=DIR/small.bvh --transition=0:1 --out=OUT/x.bvh",
    "blend --quiet --a=DIR/small.bvh --b=IN --transition=0:1 --out=OUT/x.bvh",
    "calibrate --quiet --motion=IN --markers=DIR/small.c3d --out=OUT/x.json",
    "view --motion=IN --out=OUT/x.html",
    "retarget --quiet --source=IN --target=DIR/skinned.glb --out=OUT/x.glb",
};

const char* const kMarkerCommands[] = {
    "solve --quiet --solver=dls --subject=DIR/subject.json --markers=IN --out=OUT/x.bvh",
    "repair --quiet --subject=DIR/subject.json --markers=IN --out_markers=OUT/x.c3d",
    "label --quiet --subject=DIR/subject.json --markers=IN --out=OUT/x.c3d",
    "repair --quiet --subject=DIR/subject.json --markers=IN --reference=clip --out_markers=OUT/x.c3d",
    "evaluate --quiet --subject=DIR/subject.json --markers=IN --trials=1",
    "evaluate --quiet --subject=DIR/subject.json --markers=IN --method=small_errors --trials=1",
    "filter --quiet --markers=IN --levels=2 --out=OUT/x.c3d",
    "bands --quiet --markers=IN --weights=1,1 --out=OUT/x.c3d",
    "corrupt --quiet --markers=IN --out=OUT/x.c3d",
    "view --markers=IN --out=OUT/x.html",
    "calibrate --quiet --motion=DIR/small.bvh --markers=IN --out=OUT/x.json",
    "fit_skeleton --quiet --template_subject=DIR/subject.json --markers=IN --out_subject=OUT/x.json",
    "pipeline --quiet --subject=DIR/subject.json --markers=IN --out_dir=OUT",
};

class EmptyTakeSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::TempPath("");
    dir_.pop_back();  // No trailing '/'.
    const std::string good = testing::SourcePath("tests/data/good");
    for (const char* name : {"small.bvh", "small.c3d", "markerset.json", "edit.json", "subject.json", "skinned.glb"}) {
      std::filesystem::copy_file(good + "/" + name, dir_ + "/" + name);
    }
    // `view` wants the three.js runtime before it reads its inputs: a stub will do, since
    // every view here must fail before it writes a page.
    std::filesystem::create_directory(dir_ + "/tools");
    testing::WriteTextFile(dir_ + "/tools/three.bundle.js", "// stub\n");
    ::setenv("MOCAPSOLVE_VIEWER_TOOLS", (dir_ + "/tools").c_str(), 1);
    // small.bvh with its MOTION section replaced by one of 0 frames.
    const std::string bvh = testing::ReadTextFile(good + "/small.bvh");
    testing::WriteTextFile(dir_ + "/no_frames.bvh",
                           bvh.substr(0, bvh.find("MOTION")) + "MOTION\nFrames: 0\nFrame Time: 0.0333333\n");
    MarkerTrajectories take;
    ASSERT_TRUE(ReadC3d(good + "/small.c3d", &take).ok());
    MarkerTrajectories no_frames(take.labels(), 0), all_missing(take.labels(), 5), no_points({}, kMaxFrames);
    for (MarkerTrajectories* t : {&no_frames, &all_missing, &no_points}) {
      t->frame_rate = take.frame_rate;
      t->unit = take.unit;
    }
    Write("no_frames.c3d", no_frames);
    Write("all_missing.c3d", all_missing);
    Write("no_points.c3d", no_points);
  }

  void TearDown() override { ::unsetenv("MOCAPSOLVE_VIEWER_TOOLS"); }

  void Write(const std::string& name, const MarkerTrajectories& t) {
    std::string bytes;
    ASSERT_TRUE(EncodeC3d(t, name, &bytes).ok());
    testing::WriteTextFile(dir_ + "/" + name, bytes);
  }

  // Runs `pattern` on dir_/name: exit 1, one line naming the file, nothing written.
  void ExpectRefused(const std::string& pattern, const std::string& name) {
    const std::string out = dir_ + "/out";
    std::filesystem::remove_all(out);
    std::filesystem::create_directory(out);
    const std::string command = Replaced(Replaced(Replaced(pattern, "IN", dir_ + "/" + name), "OUT", out), "DIR", dir_);
    std::string output;
    const auto start = std::chrono::steady_clock::now();
    const int code = testing::RunProgram(std::string("timeout -s KILL 60 ") + testing::CliPath(), command, &output);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    SCOPED_TRACE(command + "\n" + output);
    EXPECT_EQ(code, 1);
    EXPECT_LT(seconds, 5.0);
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << "one line";
    EXPECT_THAT(output, HasSubstr(name)) << "the message names the file";
    EXPECT_TRUE(std::filesystem::is_empty(out)) << "nothing written";
  }

  std::string dir_;
};

TEST_F(EmptyTakeSweep, EveryMotionCommandRefusesAMotionWithoutFrames) {
  for (const char* command : kMotionCommands) ExpectRefused(command, "no_frames.bvh");
}

TEST_F(EmptyTakeSweep, EveryMarkerCommandRefusesATakeWithoutData) {
  for (const char* name : {"no_frames.c3d", "all_missing.c3d", "no_points.c3d"}) {
    for (const char* command : kMarkerCommands) ExpectRefused(command, name);
  }
  ExpectRefused("convert IN OUT/x.trc", "no_points.c3d");
}

TEST_F(EmptyTakeSweep, InfoStillDescribesThem) {
  for (const char* name : {"no_frames.bvh", "no_frames.c3d", "all_missing.c3d", "no_points.c3d"}) {
    std::string output;
    EXPECT_EQ(testing::RunCli("info " + dir_ + "/" + name, &output), 0) << name << ": " << output;
  }
}

}  // namespace
}  // namespace mocapsolve
