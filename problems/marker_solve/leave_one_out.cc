#include "problems/marker_solve/leave_one_out.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "kinematics/forward_kinematics.h"
#include "kinematics/motion.h"
#include "problems/marker_label/off_body_samples.h"
#include "problems/marker_solve/sequence_solver.h"

namespace mocapsolve {
namespace {

// Nearest-rank percentile of sorted values, p in [0, 1].
double SortedPercentile(const std::vector<double>& sorted, double p) {
  const size_t rank = static_cast<size_t>(std::ceil(p * sorted.size()));
  return sorted[std::min(sorted.size(), std::max<size_t>(rank, 1)) - 1];
}

// Solves the take without marker m (the frame solve, then the clip solve when asked) with
// marker set `set`.
Status SolveWithout(const Skeleton& skeleton, const MarkerSet& set,
                    const std::vector<std::vector<Eigen::Vector3d>>& without, const LeaveOneOutOptions& options,
                    Motion* motion) {
  SequenceSolveReport sequence;
  Status status = SolveSequence(skeleton, set, without, options.frame, RestPose(skeleton), motion, &sequence);
  if (!status.ok() || !options.clip) return status;
  ClipSolveReport clip;
  return SolveClip(skeleton, set, without, options.clip_options, motion, &clip);
}

}  // namespace

// Solves the take without marker m (refining the others' offsets between solves when
// asked) and returns its prediction errors and, when `predicted` is not null, predictions.
Status LeftOutPredictionErrors(const Skeleton& skeleton, const MarkerSet& markers,
                               const std::vector<std::vector<Eigen::Vector3d>>& observed, int m,
                               const LeaveOneOutOptions& options, std::vector<double>* errors,
                               std::vector<Eigen::Vector3d>* predicted) {
  const Eigen::Vector3d missing = Eigen::Vector3d::Constant(std::nan(""));
  std::vector<std::vector<Eigen::Vector3d>> without = observed;
  for (std::vector<Eigen::Vector3d>& frame : without) frame[m] = missing;
  if (options.off_body_tolerance > 0.0) {
    // Found without m: whether another marker's sample is dropped does not depend on m's.
    const std::vector<std::vector<char>> off = OffBodySamples(skeleton, markers, without, options.off_body_tolerance);
    for (size_t f = 0; f < without.size(); ++f) {
      for (size_t n = 0; n < off[f].size(); ++n) {
        if (off[f][n]) without[f][n] = missing;
      }
    }
  }
  Motion motion;
  Status status = SolveWithout(skeleton, markers, without, options, &motion);
  MarkerSet set = markers;
  for (int round = 0; status.ok() && round < options.refine_rounds; ++round) {
    // Towards the calibrated offsets every round; m, missing from `without`, keeps its own.
    status = RefineMarkerOffsets(skeleton, markers, without, motion, options.refine, &set);
    if (status.ok()) status = SolveWithout(skeleton, set, without, options, &motion);
  }
  if (!status.ok()) return status;
  FkData fk(skeleton);
  errors->clear();
  if (predicted != nullptr) predicted->assign(observed.size(), missing);
  for (size_t f = 0; f < observed.size(); ++f) {
    if (!observed[f][m].allFinite()) continue;
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    const Eigen::Vector3d x = set.Position(m, fk);
    errors->push_back((x - observed[f][m]).norm());
    if (predicted != nullptr) (*predicted)[f] = x;
  }
  return Status::Ok();
}


PredictionErrorSummary SummarizeErrors(std::vector<double>* errors) {
  PredictionErrorSummary summary;
  if (errors->empty()) return summary;
  std::sort(errors->begin(), errors->end());
  summary.samples = static_cast<int>(errors->size());
  double sum = 0.0;
  for (double e : *errors) sum += e;
  summary.mean = sum / errors->size();
  summary.median = SortedPercentile(*errors, 0.5);
  summary.p95 = SortedPercentile(*errors, 0.95);
  summary.max = errors->back();
  return summary;
}

Status LeaveOneMarkerOut(const Skeleton& skeleton, const MarkerSet& markers,
                         const std::vector<std::vector<Eigen::Vector3d>>& observed,
                         const LeaveOneOutOptions& options, LeaveOneOutReport* report,
                         const std::function<void(int markers_done)>& progress) {
  const int num_markers = markers.num_markers();
  if (observed.empty()) return Status::Error("no frames to solve");
  for (const std::vector<Eigen::Vector3d>& frame : observed) {
    if (static_cast<int>(frame.size()) != num_markers) return Status::Error("observations do not match the marker set");
  }
  if (num_markers < 2) return Status::Error("leave-one-out needs at least 2 markers");
  std::string error;
  if (!options.frame.IsValid(&error)) return Status::Error(error);
  if (options.clip && !options.clip_options.IsValid(&error)) return Status::Error(error);
  if (options.refine_rounds < 0) return Status::Error("refine_rounds must be >= 0");
  if (!(options.off_body_tolerance >= 0.0)) return Status::Error("off_body_tolerance must be >= 0");
  const auto start = std::chrono::steady_clock::now();

  std::vector<std::vector<double>> errors(num_markers);
  std::vector<Status> statuses(num_markers, Status::Ok());
  report->predicted.assign(options.keep_predictions ? num_markers : 0, {});
  auto predicted = [&](int m) { return options.keep_predictions ? &report->predicted[m] : nullptr; };
  const int threads = std::max(1, std::min(options.num_threads, num_markers));
  if (threads == 1) {
    for (int m = 0; m < num_markers; ++m) {
      statuses[m] = LeftOutPredictionErrors(skeleton, markers, observed, m, options, &errors[m], predicted(m));
      if (progress) progress(m + 1);
    }
  } else {
    // Markers are handed out in order; each worker writes only its markers' slots, and
    // this thread reports progress as they finish.
    std::atomic<int> next{0};
    std::mutex mutex;
    std::condition_variable finished_one;
    int done = 0;
    auto work = [&] {
      for (int m = next++; m < num_markers; m = next++) {
        statuses[m] = LeftOutPredictionErrors(skeleton, markers, observed, m, options, &errors[m], predicted(m));
        std::lock_guard<std::mutex> lock(mutex);
        ++done;
        finished_one.notify_one();
      }
    };
    std::vector<std::thread> workers;
    for (int t = 0; t < threads; ++t) workers.emplace_back(work);
    std::unique_lock<std::mutex> lock(mutex);
    for (int reported = 0; reported < num_markers;) {
      finished_one.wait(lock, [&] { return done > reported; });
      reported = done;
      if (progress) {
        lock.unlock();
        progress(reported);
        lock.lock();
      }
    }
    lock.unlock();
    for (std::thread& worker : workers) worker.join();
  }

  for (int m = 0; m < num_markers; ++m) {
    if (!statuses[m].ok()) return Status::Error("without " + markers.label(m) + ": " + statuses[m].message());
  }
  std::vector<double> all;
  report->markers.assign(num_markers, PredictionErrorSummary());
  for (int m = 0; m < num_markers; ++m) {
    all.insert(all.end(), errors[m].begin(), errors[m].end());
    report->markers[m] = SummarizeErrors(&errors[m]);
  }
  report->all = SummarizeErrors(&all);
  if (options.off_body_tolerance > 0.0) {
    const std::vector<std::vector<char>> off = OffBodySamples(skeleton, markers, observed, options.off_body_tolerance);
    for (size_t f = 0; f < observed.size(); ++f) {
      for (int m = 0; m < num_markers; ++m) {
        if (off[f][m] && observed[f][m].allFinite()) ++report->markers[m].off_body, ++report->all.off_body;
      }
    }
  }
  report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return Status::Ok();
}

}  // namespace mocapsolve
