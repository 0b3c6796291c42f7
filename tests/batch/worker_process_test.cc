// Worker processes: exit codes, signals, timeouts and the last stderr line of children
// run with /bin/sh, several at a time.
#include "batch/worker_process.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

std::vector<WorkerResult> RunScripts(const std::vector<std::string>& scripts, int jobs, const WorkerLimits& limits) {
  std::vector<WorkerJob> work;
  for (size_t i = 0; i < scripts.size(); ++i) {
    work.push_back({"job" + std::to_string(i), {"/bin/sh", "-c", scripts[i]}});
  }
  std::vector<WorkerResult> results(scripts.size());
  WorkerCallbacks callbacks;
  callbacks.on_done = [&](int index, const WorkerResult& result) { results[index] = result; };
  RunWorkers(work, jobs, limits, callbacks);
  return results;
}

TEST(RunWorkers, ExitCodesSignalsAndLastLines) {
  const std::vector<WorkerResult> results =
      RunScripts({"echo out; exit 0", "echo first >&2; echo 'the reason' >&2; echo >&2; exit 3", "kill -SEGV $$",
           "printf 'progress 1\\rprogress 2' >&2; exit 1", "exec /nonexistent/binary"},
          2, WorkerLimits());
  EXPECT_TRUE(results[0].ok());
  EXPECT_EQ(results[0].ExitName(), "0");
  EXPECT_EQ(results[1].exit_code, 3);
  EXPECT_EQ(results[1].last_line, "the reason");
  EXPECT_EQ(results[2].ExitName(), "SIGSEGV");
  EXPECT_FALSE(results[2].ok());
  EXPECT_EQ(results[3].last_line, "progress 2");
  EXPECT_NE(results[4].exit_code, 0);
}

TEST(RunWorkers, TimeoutKillsOnlyTheSlowOne) {
  WorkerLimits limits;
  limits.timeout_seconds = 0.3;
  const std::vector<WorkerResult> results = RunScripts({"sleep 30", "exit 0"}, 2, limits);
  EXPECT_TRUE(results[0].timed_out);
  EXPECT_EQ(results[0].ExitName(), "timeout");
  EXPECT_LT(results[0].seconds, 5.0);
  EXPECT_TRUE(results[1].ok());
}

TEST(RunWorkers, StartCanVetoAJob) {
  std::vector<WorkerJob> work = {{"a", {"/bin/sh", "-c", "exit 0"}}, {"b", {"/bin/sh", "-c", "exit 0"}}};
  int done = 0;
  WorkerCallbacks callbacks;
  callbacks.on_start = [](int index) { return index == 1; };
  callbacks.on_done = [&](int index, const WorkerResult& result) {
    EXPECT_EQ(index, 1);
    EXPECT_TRUE(result.ok());
    ++done;
  };
  RunWorkers(work, 1, WorkerLimits(), callbacks);
  EXPECT_EQ(done, 1);
}

TEST(RunAndCapture, StdoutAndFailure) {
  std::string output;
  ASSERT_TRUE(RunAndCapture({"/bin/sh", "-c", "echo hello"}, &output).ok());
  EXPECT_EQ(output, "hello\n");
  const Status status = RunAndCapture({"/bin/sh", "-c", "echo bad >&2; exit 1"}, &output);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("bad"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace mocapsolve
