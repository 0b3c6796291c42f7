#include "pipeline/in_order_worker.h"

#include <algorithm>
#include <exception>
#include <type_traits>
#include <utility>

namespace mocapsolve {
namespace {

// A job's part as a Status: an exception it throws as an error (it must not leave a thread).
template <typename Part>
Status RunPart(const Part& part) {
  try {
    if constexpr (std::is_same_v<decltype(part()), Status>) {
      return part();
    } else {
      part();
      return Status::Ok();
    }
  } catch (const std::exception& e) {
    return Status::Error(e.what());
  } catch (...) {
    return Status::Error("unknown exception");
  }
}

}  // namespace

InOrderWorker::InOrderWorker(bool threaded) : threaded_(threaded) {
  if (threaded_) thread_ = std::thread(&InOrderWorker::Loop, this);
}

InOrderWorker::~InOrderWorker() { static_cast<void>(Finish()); }

bool InOrderWorker::Submit(Run run, Keep keep) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (failed_ || closed_) return false;
  Job job{given_++, std::move(run), std::move(keep)};
  if (threaded_) {
    Job older;  // The worker is busy: this thread runs the job that waits.
    TakeWaiting(&older);
    waiting_ = std::move(job);
    job = std::move(older);
    changed_.notify_all();
  }
  if (job.run) {
    lock.unlock();
    Complete(std::move(job));
    lock.lock();
  }
  return !failed_;
}

Status InOrderWorker::Finish() {
  if (threaded_) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    changed_.notify_all();
    for (;;) {  // This thread runs what waits, beside the worker's job.
      Job job;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!TakeWaiting(&job)) break;
      }
      changed_.notify_all();
      Complete(std::move(job));
    }
    if (thread_.joinable()) thread_.join();
  }
  std::lock_guard<std::mutex> lock(mutex_);
  closed_ = true;
  return error_;
}

bool InOrderWorker::TakeWaiting(Job* job) {
  if (!waiting_.run || failed_) return false;
  *job = std::move(waiting_);
  waiting_ = Job();
  return true;
}

void InOrderWorker::Complete(Job job) {
  Done done{job.index, RunPart(job.run), std::move(job.keep)};
  job = Job();  // What only the run held, freed.
  std::unique_lock<std::mutex> lock(mutex_);
  done_.push_back(std::move(done));
  if (keeping_) return;  // That thread keeps this job in its turn.
  keeping_ = true;
  for (;;) {
    const auto next = std::find_if(done_.begin(), done_.end(), [&](const Done& d) { return d.index == turn_; });
    if (next == done_.end()) break;
    Done turn = std::move(*next);
    done_.erase(next);
    if (!failed_) {
      if (turn.status.ok() && turn.keep) {
        lock.unlock();  // Its turn: no other thread keeps while keeping_ is set.
        turn.status = RunPart(turn.keep);
        lock.lock();
      }
      if (!turn.status.ok()) {
        failed_ = true;
        error_ = turn.status;
        waiting_ = Job();  // Given after the failed one: not run.
      }
    }
    ++turn_;
    turn = Done();  // Its data freed before the next turn.
  }
  keeping_ = false;
  lock.unlock();
  changed_.notify_all();
}

void InOrderWorker::Loop() {
  for (;;) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return static_cast<bool>(waiting_.run) || closed_ || failed_; });
      if (!TakeWaiting(&job)) return;  // Closed or failed, and nothing to run.
    }
    changed_.notify_all();
    Complete(std::move(job));
  }
}

}  // namespace mocapsolve
