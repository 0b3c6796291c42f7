// Worker processes: each take of a batch runs in its own process (fork + exec of the
// mocapsolve binary), so a crash, abort, timeout or out-of-memory in one take never stops
// the others. RunWorkers keeps up to `jobs` of them running, one poll() loop in the
// calling thread:
//   - the child gets stdin and stdout from /dev/null, stderr into a pipe (its last
//     non-empty line is the take's one-line error), its own process group, a kill on
//     the batch's death (PR_SET_PDEATHSIG SIGKILL: killing the batch loses only the
//     takes in flight), and RLIMIT_AS = memory_mb when > 0;
//   - a worker running longer than timeout_seconds (> 0) gets SIGKILL (its group);
//   - the result: exit code, or the signal, or "timeout".
// Test hook: with MOCAPSOLVE_TEST_CRASH_TAKE=<label>[:KILL],... in the environment, the
// worker of each label raises SIGABRT (or SIGKILL) instead of exec (crashing workers).
#ifndef MOCAPSOLVE_BATCH_WORKER_PROCESS_H_
#define MOCAPSOLVE_BATCH_WORKER_PROCESS_H_

#include <functional>
#include <string>
#include <vector>

#include "kinematics/status.h"

namespace mocapsolve {

struct WorkerLimits {
  double timeout_seconds = 0.0;  // 0 = none.
  long memory_mb = 0;            // RLIMIT_AS of the child; 0 = none.
};

struct WorkerResult {
  bool started = false;
  int exit_code = -1;       // When exited normally.
  int signal = 0;           // When killed by a signal.
  bool timed_out = false;
  std::string last_line;    // The last non-empty stderr line.
  double seconds = 0.0;     // Wall time.

  bool ok() const { return started && signal == 0 && !timed_out && exit_code == 0; }
  // "0", "3", "SIGSEGV", "timeout", "not started".
  std::string ExitName() const;
};

struct WorkerJob {
  std::string label;                   // For the test hook and messages.
  std::vector<std::string> argv;       // argv[0] is the executable path.
};

// Called (in the calling thread) when a worker starts and when it ends.
struct WorkerCallbacks {
  // Called right before job `index` starts: may do the job's preparation and veto it by
  // returning false (then on_done is not called for it).
  std::function<bool(int index)> on_start;
  std::function<void(int index, const WorkerResult& result)> on_done;
  std::function<void()> on_tick;       // About every 100 ms while workers run.
};

// Runs the jobs in order, at most `jobs` at a time, and returns when all have ended.
void RunWorkers(const std::vector<WorkerJob>& work, int jobs, const WorkerLimits& limits,
                const WorkerCallbacks& callbacks);

// Runs one command to its end and captures its stdout (for `pipeline --print_config`).
Status RunAndCapture(const std::vector<std::string>& argv, std::string* output);

// The running binary's path (readlink /proc/self/exe).
std::string SelfExecutable();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_BATCH_WORKER_PROCESS_H_
