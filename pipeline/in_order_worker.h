// InOrderWorker: jobs run one after another, in the order they were given, on one worker
// thread beside the caller's, with at most one job waiting (so a job's data, a window of a
// long take, is held for at most two jobs at once beyond the caller's own). A windowed take
// (pipeline/take_windows.h) hands it each window's character stage while its own thread
// repairs the next window: the order of the jobs is the order of their effects (the
// character takes appended, the figures summed), so the results are the same bytes as with
// the jobs run inline.
//
// Errors: the first job that fails (a Status error, or an exception it throws: its what())
// stops the worker; the jobs given after it are not run, Submit says so, and Finish gives
// that error. Without a thread (threaded = false) each job runs inside Submit, with the
// same rules.
#ifndef MOCAPSOLVE_PIPELINE_IN_ORDER_WORKER_H_
#define MOCAPSOLVE_PIPELINE_IN_ORDER_WORKER_H_

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

#include "kinematics/status.h"

namespace mocapsolve {

class InOrderWorker {
 public:
  using Job = std::function<Status()>;

  explicit InOrderWorker(bool threaded);
  ~InOrderWorker();  // Finish(), its error dropped (call Finish to see it).
  InOrderWorker(const InOrderWorker&) = delete;
  InOrderWorker& operator=(const InOrderWorker&) = delete;

  // Runs `job` after the jobs given before it; waits while one job is already waiting.
  // False, the job not run, once a job has failed.
  bool Submit(Job job);
  // Waits for the jobs given; the first failed job's error, else Ok. Submit is refused after it.
  Status Finish();

 private:
  void Loop();

  bool threaded_;
  std::mutex mutex_;
  std::condition_variable changed_;
  Job waiting_;           // Empty when no job waits.
  bool closed_ = false;   // Finish called: no more jobs.
  bool failed_ = false;
  Status error_ = Status::Ok();
  std::thread thread_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_IN_ORDER_WORKER_H_
