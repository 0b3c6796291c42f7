#include "pipeline/in_order_worker.h"

#include <exception>
#include <utility>

namespace mocapsolve {
namespace {

// A job's Status, an exception it throws as an error (it must not leave the worker thread).
Status RunJob(const InOrderWorker::Job& job) {
  try {
    return job();
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

bool InOrderWorker::Submit(Job job) {
  if (!threaded_) {
    if (failed_ || closed_) return false;
    const Status status = RunJob(job);
    if (!status.ok()) {
      failed_ = true;
      error_ = status;
    }
    return status.ok();
  }
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return !waiting_ || failed_ || closed_; });
  if (failed_ || closed_) return false;
  waiting_ = std::move(job);
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
    if (thread_.joinable()) thread_.join();
  }
  closed_ = true;
  return error_;
}

void InOrderWorker::Loop() {
  for (;;) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return static_cast<bool>(waiting_) || closed_; });
      if (!waiting_) return;  // Closed and nothing waits.
      job = std::move(waiting_);
      waiting_ = nullptr;
    }
    changed_.notify_all();  // A place to wait is free.
    const Status status = RunJob(job);
    job = nullptr;  // Its data freed before the next job is taken.
    if (status.ok()) continue;
    std::lock_guard<std::mutex> lock(mutex_);
    failed_ = true;
    error_ = status;
    waiting_ = nullptr;  // Given after the failed one: not run.
    changed_.notify_all();
    return;
  }
}

}  // namespace mocapsolve
