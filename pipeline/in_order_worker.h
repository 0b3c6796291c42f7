// InOrderWorker: jobs whose effects are kept in the order they were given, with their work
// run on one worker thread beside the caller's, at most one job waiting (so a job's data, a
// window of a long take, is held for at most two jobs at once beyond the caller's own). A
// job is two parts: `run`, its work, which needs nothing from the jobs before it, and
// `keep`, its effects (the character takes appended, the figures summed), run after the
// jobs given before it have kept theirs, one keep at a time. A windowed take
// (pipeline/take_windows.h) hands it each window's character stage while its own thread
// repairs the next window; once the caller has no more jobs, Finish runs the waiting job on
// the caller's thread beside the worker's running one (the last window's retarget no longer
// waits for the one before it). The order of the keeps is the order given, so the results
// are the same bytes as with the jobs run inline.
//
// Errors: the first job (in the order given) whose run fails (a Status error, or an
// exception it throws: its what()) stops the worker; the jobs after it are not kept, the
// waiting one not run, Submit says so, and Finish gives that error. Without a thread
// (threaded = false) each job runs and keeps inside Submit, with the same rules.
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
  using Run = std::function<Status()>;
  using Keep = std::function<void()>;

  explicit InOrderWorker(bool threaded);
  ~InOrderWorker();  // Finish(), its error dropped (call Finish to see it).
  InOrderWorker(const InOrderWorker&) = delete;
  InOrderWorker& operator=(const InOrderWorker&) = delete;

  // Gives a job (keep may be empty); waits while one job is already waiting. False, the job
  // not run, once a job has failed.
  bool Submit(Run run, Keep keep = nullptr);
  // No more jobs: runs the waiting one on this thread, waits for the worker's, and gives the
  // first failed job's error, else Ok. Submit is refused after it.
  Status Finish();

 private:
  struct Job {
    long index = 0;  // Its place in the order given.
    Run run;
    Keep keep;
  };

  void Loop();
  // Runs a job taken from waiting_ (on either thread), then keeps it in its turn.
  void Complete(Job job);
  // Moves the waiting job into *job (false when none waits or a job failed); needs mutex_.
  bool TakeWaiting(Job* job);

  bool threaded_;
  std::mutex mutex_;
  std::condition_variable changed_;
  Job waiting_;               // Its run is empty when no job waits.
  long given_ = 0;            // Jobs given.
  long turn_ = 0;             // The index of the next job to keep.
  bool closed_ = false;       // Finish called: no more jobs.
  bool failed_ = false;
  Status error_ = Status::Ok();
  std::thread thread_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_IN_ORDER_WORKER_H_
