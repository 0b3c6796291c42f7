// InOrderWorker: jobs whose effects are kept in the order they were given, their work run
// on one worker thread beside the caller's, at most one job waiting. A job is two parts:
// `run`, its work, which needs nothing from the jobs before it, and `keep`, its effects
// (the character takes appended, the figures summed), run once the jobs given before it
// have kept theirs, one keep at a time, by whichever thread finishes the job that was
// holding the turn (a job done early waits in a short list, not on a thread). A windowed
// take (pipeline/take_windows.h) hands it each window's character stage while its own
// thread repairs the next window. The caller's thread never idles while work waits: a
// Submit that finds a job already waiting runs that job itself (the worker is busy with
// the one before it) and leaves the new one waiting, and Finish runs the waiting job beside
// the worker's. So both threads stay busy whichever stage is the longer, and at most three
// jobs' data are held at once (one running on each thread, one waiting), one of them
// instead of the caller's own work. The keeps' order is the order given, so the results
// are the same bytes as with the jobs run inline.
//
// Errors: the first job (in the order given) whose run or keep fails (a Status error, or
// an exception it throws: its what()) stops the worker; the jobs after it are not kept, the
// waiting one not run, Submit says so, and Finish gives that error. Without a thread
// (threaded = false) each job runs and keeps inside Submit, with the same rules.
#ifndef MOCAPSOLVE_PIPELINE_IN_ORDER_WORKER_H_
#define MOCAPSOLVE_PIPELINE_IN_ORDER_WORKER_H_

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "kinematics/status.h"

namespace mocapsolve {

class InOrderWorker {
 public:
  using Run = std::function<Status()>;
  using Keep = std::function<Status()>;

  explicit InOrderWorker(bool threaded);
  ~InOrderWorker();  // Finish(), its error dropped (call Finish to see it).
  InOrderWorker(const InOrderWorker&) = delete;
  InOrderWorker& operator=(const InOrderWorker&) = delete;

  // Gives a job (keep may be empty). When a job already waits, runs that one on this
  // thread first. False once a job has failed (this job then not run).
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
  struct Done {  // A job run, its keep not yet run.
    long index = 0;
    Status status = Status::Ok();
    Keep keep;
  };

  void Loop();
  // Runs a job taken from waiting_ (on either thread), then keeps every done job whose turn
  // has come, unless another thread is keeping them.
  void Complete(Job job);
  // Moves the waiting job into *job (false when none waits or a job failed); needs mutex_.
  bool TakeWaiting(Job* job);

  bool threaded_;
  std::mutex mutex_;
  std::condition_variable changed_;
  Job waiting_;             // Its run is empty when no job waits.
  std::vector<Done> done_;  // Run, waiting for their turn to keep.
  long given_ = 0;          // Jobs given.
  long turn_ = 0;           // The index of the next job to keep.
  bool keeping_ = false;    // A thread is running keeps.
  bool closed_ = false;     // Finish called: no more jobs.
  bool failed_ = false;
  Status error_ = Status::Ok();
  std::thread thread_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_IN_ORDER_WORKER_H_
