// InOrderWorker (pipeline/in_order_worker.h): jobs kept in the order given, whichever takes
// longer; at most one job waits; Finish runs the waiting job beside the worker's; the first
// failed job (a Status error or an exception) stops the ones after it and is what Finish
// returns, with and without a thread.
#include "pipeline/in_order_worker.h"

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// Waits until `flag` is set, at most 5 s (a test that would hang fails instead); its value.
bool WaitFor(const std::atomic<bool>& flag) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!flag && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return flag;
}

// A keep that records job k's turn.
InOrderWorker::Keep KeepIndex(std::vector<int>* kept, int k) {
  return [kept, k] {
    kept->push_back(k);
    return Status::Ok();
  };
}

class InOrderWorkerTest : public ::testing::TestWithParam<bool> {};

// The earlier jobs take longer: run side by side, they would finish last.
TEST_P(InOrderWorkerTest, KeepsJobsInTheOrderGiven) {
  std::vector<int> done;  // Only the keeps touch it, one at a time.
  InOrderWorker worker(GetParam());
  for (int k = 0; k < 12; ++k) {
    ASSERT_TRUE(worker.Submit(
        [k] {
          std::this_thread::sleep_for(std::chrono::milliseconds(3 * (12 - k)));
          return Status::Ok();
        },
        [&done, k] {
          done.push_back(k);
          return Status::Ok();
        }));
  }
  EXPECT_TRUE(worker.Finish().ok());
  ASSERT_EQ(done.size(), 12u);
  for (int k = 0; k < 12; ++k) EXPECT_EQ(done[k], k);
  EXPECT_FALSE(worker.Submit([] { return Status::Ok(); })) << "no job after Finish";
}

TEST_P(InOrderWorkerTest, FirstErrorStopsTheJobsAfterIt) {
  std::vector<int> done;
  InOrderWorker worker(GetParam());
  int given = 0;
  for (int k = 0; k < 8; ++k) {
    const bool submitted = worker.Submit(
        [k] {
          if (k == 3) return Status::Error("window 4: failed");
          if (k == 5) return Status::Error("window 6: failed too");
          return Status::Ok();
        },
        [&done, k] {
          done.push_back(k);
          return Status::Ok();
        });
    if (!submitted) break;
    ++given;
  }
  const Status status = worker.Finish();
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), "window 4: failed");
  EXPECT_EQ(done, (std::vector<int>{0, 1, 2}));
  // Inline, the failed job's Submit says it failed (3 given); with the thread it was given,
  // and more may have been given before its turn came.
  EXPECT_GE(given, 3);
  if (!GetParam()) {
    EXPECT_EQ(given, 3);
  }
}

TEST_P(InOrderWorkerTest, AnExceptionIsAnErrorOfOneLine) {
  InOrderWorker worker(GetParam());
  bool after = false;
  worker.Submit([]() -> Status { throw std::runtime_error("retarget: out of memory"); });
  worker.Submit([] { return Status::Ok(); }, [&after] {
    after = true;
    return Status::Ok();
  });
  const Status status = worker.Finish();
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), "retarget: out of memory");
  EXPECT_FALSE(after);
}

INSTANTIATE_TEST_SUITE_P(ThreadedOrInline, InOrderWorkerTest, ::testing::Bool());

// One job running, one waiting: a third Submit runs the waiting job on the caller's thread
// (the first sees it start) and leaves the third waiting; the second, done before the
// first, is kept after it, by the worker, and the third after both.
TEST(InOrderWorker, ASubmitThatFindsAJobWaitingRunsItOnTheCallersThread) {
  InOrderWorker worker(true);
  std::atomic<bool> first_started{false}, second_started{false}, first_saw_second{false};
  std::vector<int> kept;
  ASSERT_TRUE(worker.Submit(
      [&] {
        first_started = true;
        first_saw_second = WaitFor(second_started);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));  // Done after the second.
        return Status::Ok();
      },
      KeepIndex(&kept, 0)));
  ASSERT_TRUE(WaitFor(first_started));
  std::thread::id second_thread;
  ASSERT_TRUE(worker.Submit(
      [&] {
        second_thread = std::this_thread::get_id();
        second_started = true;
        return Status::Ok();
      },
      KeepIndex(&kept, 1)));
  ASSERT_TRUE(worker.Submit([] { return Status::Ok(); }, KeepIndex(&kept, 2)));
  EXPECT_EQ(second_thread, std::this_thread::get_id());
  EXPECT_TRUE(worker.Finish().ok());
  EXPECT_TRUE(first_saw_second) << "the waiting job was not run beside the running one";
  EXPECT_EQ(kept, (std::vector<int>{0, 1, 2}));
}

// Once no more jobs come, the waiting job runs on the caller's thread while the worker's
// runs: the first job waits (up to 5 s) to see the second start. The keeps stay in order.
TEST(InOrderWorker, FinishRunsTheWaitingJobBesideTheRunningOne) {
  InOrderWorker worker(true);
  std::atomic<bool> first_started{false}, second_started{false}, first_saw_second{false};
  std::vector<int> kept;
  ASSERT_TRUE(worker.Submit(
      [&] {
        first_started = true;
        first_saw_second = WaitFor(second_started);
        return Status::Ok();
      },
      KeepIndex(&kept, 0)));
  ASSERT_TRUE(WaitFor(first_started));
  const std::thread::id caller = std::this_thread::get_id();
  std::thread::id second_thread;
  ASSERT_TRUE(worker.Submit(
      [&] {
        second_thread = std::this_thread::get_id();
        second_started = true;
        return Status::Ok();
      },
      KeepIndex(&kept, 1)));
  EXPECT_TRUE(worker.Finish().ok());
  EXPECT_TRUE(first_saw_second) << "the waiting job ran only after the running one";
  EXPECT_EQ(second_thread, caller);
  EXPECT_EQ(kept, (std::vector<int>{0, 1}));
}

// A job whose run fails after a later one (run beside it) succeeded: the error is the
// earlier job's, and the later job is not kept.
TEST(InOrderWorker, AnEarlierJobsErrorWinsOverALaterJobRunBesideIt) {
  InOrderWorker worker(true);
  std::atomic<bool> first_started{false}, second_done{false};
  std::vector<int> kept;
  ASSERT_TRUE(worker.Submit(
      [&] {
        first_started = true;
        WaitFor(second_done);
        return Status::Error("window 1: failed");
      },
      KeepIndex(&kept, 0)));
  ASSERT_TRUE(WaitFor(first_started));
  ASSERT_TRUE(worker.Submit(
      [&] {
        second_done = true;
        return Status::Ok();
      },
      KeepIndex(&kept, 1)));
  const Status status = worker.Finish();
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), "window 1: failed");
  EXPECT_TRUE(kept.empty());
}

}  // namespace
}  // namespace mocapsolve
