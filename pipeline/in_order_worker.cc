#include "pipeline/in_order_worker.h"

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
  if (!threaded_) {
    if (failed_ || closed_) return false;
    const long index = given_++;
    lock.unlock();
    Complete(Job{index, std::move(run), std::move(keep)});
    lock.lock();
    return !failed_;
  }
  changed_.wait(lock, [&] { return !waiting_.run || failed_ || closed_; });
  if (failed_ || closed_) return false;
  waiting_ = Job{given_++, std::move(run), std::move(keep)};
  changed_.notify_all();
  return true;
}

Status InOrderWorker::Finish() {
  if (threaded_) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    changed_.notify_all();
    for (;;) {  // The caller's thread runs what waits, beside the worker's job.
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
  Status status = RunPart(job.run);
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return turn_ == job.index; });
  if (!failed_) {
    if (status.ok() && job.keep) {
      lock.unlock();  // Its turn: no other job keeps until turn_ moves on.
      status = RunPart(job.keep);
      lock.lock();
    }
    if (!status.ok()) {
      failed_ = true;
      error_ = status;
      waiting_ = Job();  // Given after the failed one: not run.
    }
  }
  ++turn_;
  lock.unlock();
  changed_.notify_all();
  job = Job();  // Its data freed before the next job is taken.
}

void InOrderWorker::Loop() {
  for (;;) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return static_cast<bool>(waiting_.run) || closed_ || failed_; });
      if (!TakeWaiting(&job)) return;  // Closed or failed, and nothing to run.
    }
    changed_.notify_all();  // A place to wait is free.
    Complete(std::move(job));
  }
}

}  // namespace mocapsolve
