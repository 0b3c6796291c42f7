#include "batch/batch_runner.h"

#include <dirent.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <unordered_map>
#include <utility>

#include "io/atomic_file.h"
#include "io/file_transaction.h"

namespace mocapsolve {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

bool FileExists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

double Now() {
  struct timespec now;
  ::clock_gettime(CLOCK_REALTIME, &now);
  return now.tv_sec + 1e-9 * now.tv_nsec;
}

// The files of a take folder besides the record modified at or after `since` (seconds
// since the epoch; files an earlier, unrecorded run left are not the take's), sorted.
std::vector<std::string> FolderFiles(const std::string& folder, double since) {
  std::vector<std::string> names;
  DIR* dir = ::opendir(folder.c_str());
  if (dir == nullptr) return names;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (name == "." || name == ".." || name == "record.json") continue;
    struct stat st;
    if (::stat((folder + "/" + name).c_str(), &st) != 0) continue;
    if (st.st_mtim.tv_sec + 1e-9 * st.st_mtim.tv_nsec < since) continue;
    names.push_back(name);
  }
  ::closedir(dir);
  std::sort(names.begin(), names.end());
  return names;
}

// Creates the work folder, or empties it: the configs a killed batch left go now.
Status ResetWorkFolder(const std::string& folder) {
  Status status = MakeFolders(folder);
  if (!status.ok()) return status;
  DIR* dir = ::opendir(folder.c_str());
  if (dir == nullptr) return Status::Error(folder + ": cannot read the batch's work folder");
  std::vector<std::string> stale;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (name != "." && name != "..") stale.push_back(folder + "/" + name);
  }
  ::closedir(dir);
  for (const std::string& path : stale) ::unlink(path.c_str());
  return Status::Ok();
}

Status WriteText(const std::string& path, const std::string& text) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return Status::Error(path + ": cannot write the file");
  const bool ok = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  return std::fclose(file) == 0 && ok ? Status::Ok() : Status::Error(path + ": cannot write the file");
}

bool IsFailure(const std::string& status) { return status == "failed" || status == "gate_failed"; }

struct TakeState {
  TakeKey key;
  std::string config_path;
  double started = 0.0;  // Seconds since the epoch.
};

// One run of RunBatch: the takes' callbacks for RunWorkers and the counts.
class BatchRun {
 public:
  BatchRun(const BatchManifest& manifest, const BatchRunOptions& options,
           const std::function<void(const BatchProgress&)>& progress)
      : manifest_(manifest), options_(options), progress_(progress), start_(Clock::now()),
        work_dir_(options.work_dir.empty() ? options.out_dir + "/.batch-work" : options.work_dir),
        n_(static_cast<int>(manifest.takes.size())), work_(n_) {
    out_.takes.resize(n_);
  }

  Status Run(BatchResult* result);

 private:
  std::string TakeDir(int i) const { return options_.out_dir + "/" + manifest_.takes[i].name; }
  bool Start(int i);
  bool SkipUnchanged(int i, const std::string& key);
  std::vector<std::string> WorkerArgv(int i, const std::string& config_path) const;
  void Done(int i, const WorkerResult& worker);
  TakeRecord WorkerRecord(int i, const TakeState& state, const WorkerResult& worker) const;
  TakeRecord FailedRecord(int i, const std::string& error) const;
  void Finish(int i, TakeRecord record, bool ran, Clock::time_point t0);
  void Report();
  void Checkpoint();

  const BatchManifest& manifest_;
  const BatchRunOptions& options_;
  const std::function<void(const BatchProgress&)>& progress_;
  const Clock::time_point start_;
  const std::string work_dir_;
  const int n_;
  BatchResult out_;
  std::vector<WorkerJob> work_;                 // Filled when a take starts, emptied when it ends.
  std::unordered_map<int, TakeState> running_;  // The takes in flight only.
  TakeKeyCache cache_;
  double own_ = 0.0, ran_seconds_ = 0.0;
  int ran_ended_ = 0;
  long frames_ = 0;
  Clock::time_point last_checkpoint_ = Clock::now();
  double checkpoint_cost_ = 0.0;
};

Status BatchRun::Run(BatchResult* result) {
  Status status = MakeFolders(options_.out_dir);
  if (status.ok()) status = ResetWorkFolder(work_dir_);
  if (!status.ok()) return status;
  WorkerCallbacks callbacks;
  callbacks.on_start = [this](int i) { return Start(i); };
  callbacks.on_done = [this](int i, const WorkerResult& worker) { Done(i, worker); };
  callbacks.on_tick = [this]() { Report(); };
  RunWorkers(work_, options_.jobs, options_.limits, callbacks);
  ::rmdir(work_dir_.c_str());
  out_.seconds = Since(start_);
  out_.own_seconds = own_;
  Report();
  *result = std::move(out_);
  return Status::Ok();
}

// The takes' files (subject, records, reports) are read by every take: not recorded as the
// batch's inputs (the workers guard their own), so the batch stays flat in memory.
bool BatchRun::Start(int i) {
  FileTransaction::UntrackedReads untracked;
  const auto t0 = Clock::now();
  const BatchTake& take = manifest_.takes[i];
  TakeState state;
  Status s = ComputeTakeKey(manifest_, take, options_.version, &state.key, &cache_);
  if (!s.ok()) {  // A missing or unreadable input: the take fails before any worker; no record.
    Finish(i, FailedRecord(i, s.message()), true, t0);
    return false;
  }
  if (SkipUnchanged(i, HexHash(state.key.key))) {
    own_ += Since(t0);
    return false;
  }
  state.config_path = work_dir_ + "/" + std::to_string(i) + ".json";
  s = WriteText(state.config_path, state.key.given_json + "\n");
  if (!s.ok()) {
    Finish(i, FailedRecord(i, s.message()), true, t0);
    return false;
  }
  work_[i].label = take.name;
  work_[i].argv = WorkerArgv(i, state.config_path);
  state.started = Now();
  running_.emplace(i, std::move(state));
  own_ += Since(t0);
  return true;
}

// True if the take's record has the same key and is to be kept (done with its outputs, or
// failed without retry_failed): then the take is finished as skipped. Otherwise the old
// record (first: from then the folder's outputs are claimed by no key) and its outputs go.
bool BatchRun::SkipUnchanged(int i, const std::string& key) {
  const std::string dir = TakeDir(i);
  TakeRecord old;
  const bool has_record = FileExists(RecordPath(dir)) && ReadTakeRecord(RecordPath(dir), &old).ok();
  if (has_record && !options_.force && old.key == key) {
    bool outputs = true;
    for (const std::string& file : old.outputs) outputs = outputs && FileExists(dir + "/" + file);
    if ((old.status == "done" && outputs) || (IsFailure(old.status) && !options_.retry_failed)) {
      Finish(i, std::move(old), false, Clock::now());
      return true;
    }
  }
  if (has_record) {
    ::unlink(RecordPath(dir).c_str());
    for (const std::string& file : old.outputs) {
      if (file.find('/') == std::string::npos) ::unlink((dir + "/" + file).c_str());
    }
  }
  return false;
}

std::vector<std::string> BatchRun::WorkerArgv(int i, const std::string& config_path) const {
  const BatchTake& take = manifest_.takes[i];
  std::vector<std::string> argv = {options_.executable, "pipeline", "--quiet", "--subject=" + take.subject,
                                   "--markers=" + take.markers, "--out_dir=" + TakeDir(i),
                                   "--config=" + config_path};
  if (options_.take_threads > 0 && !TakeGivesOption(manifest_, take, "num_threads")) {
    argv.push_back("--num_threads=" + std::to_string(options_.take_threads));
  }
  if (!take.characters.empty()) {
    std::string list;
    for (const std::string& c : take.characters) list += (list.empty() ? "" : ",") + c;
    argv.push_back("--character=" + list);
  }
  return argv;
}

void BatchRun::Done(int i, const WorkerResult& worker) {
  FileTransaction::UntrackedReads untracked;
  const auto t0 = Clock::now();
  const auto found = running_.find(i);
  const TakeState state = std::move(found->second);
  running_.erase(found);
  ::unlink(state.config_path.c_str());
  TakeRecord record = WorkerRecord(i, state, worker);
  // A worker that produced nothing: its folder is made for the record alone.
  Status s = MakeFolders(TakeDir(i));
  if (s.ok()) s = WriteTakeRecord(TakeDir(i), record);
  if (!s.ok()) {
    record.status = "failed";
    record.error += (record.error.empty() ? "" : "; ") + std::string("cannot write the record: ") + s.message();
  }
  frames_ += record.figures.frames;
  ran_seconds_ += worker.seconds;
  ++ran_ended_;
  Finish(i, std::move(record), true, t0);
}

TakeRecord BatchRun::WorkerRecord(int i, const TakeState& state, const WorkerResult& worker) const {
  TakeRecord record;
  record.take = manifest_.takes[i].name;
  record.key = HexHash(state.key.key);
  record.program_version = options_.version;
  record.inputs = state.key.inputs;
  record.options_json = state.key.options_json;
  record.given_json = state.key.given_json;
  record.exit = worker.ExitName();
  record.exit_code = worker.exit_code;
  record.wall_seconds = worker.seconds;
  const bool gate_failed = worker.started && worker.signal == 0 && !worker.timed_out && worker.exit_code == 3;
  record.status = worker.ok() ? "done" : gate_failed ? "gate_failed" : "failed";
  if (!worker.ok()) {
    record.error = worker.last_line.empty() ? "the worker ended with " + record.exit : worker.last_line;
    if (worker.timed_out) {
      char text[64];
      std::snprintf(text, sizeof(text), "timed out after %.3g s", options_.limits.timeout_seconds);
      record.error = std::string(text) + (worker.last_line.empty() ? "" : ": " + worker.last_line);
    }
  }
  if (worker.ok() || gate_failed) {  // The pipeline wrote its outputs.
    const std::string dir = TakeDir(i);
    Status s = TakeFiguresFromReport(dir + "/report.json", &record.figures);
    if (!s.ok() && worker.ok()) {
      record.status = "failed";
      record.error = s.message();
    }
    // Less a second: file systems with coarse timestamps.
    record.outputs = FolderFiles(dir, state.started - 1.0);
  }
  return record;
}

TakeRecord BatchRun::FailedRecord(int i, const std::string& error) const {
  TakeRecord record;
  record.take = manifest_.takes[i].name;
  record.program_version = options_.version;
  record.status = "failed";
  record.exit = "1";
  record.exit_code = 1;
  record.error = error;
  return record;
}

void BatchRun::Finish(int i, TakeRecord record, bool ran, Clock::time_point t0) {
  out_.done += record.status == "done";
  out_.failed += record.status != "done";
  out_.gate_failed += record.status == "gate_failed";
  (ran ? out_.ran : out_.skipped) += 1;
  out_.takes[i].record = SummaryOf(std::move(record));
  out_.takes[i].ran = ran;
  work_[i] = WorkerJob();
  own_ += Since(t0);
  Report();
  Checkpoint();
}

void BatchRun::Report() {
  if (!progress_) return;
  BatchProgress p;
  p.takes = n_;
  p.done = out_.done;
  p.failed = out_.failed;
  p.skipped = out_.skipped;
  p.running = static_cast<int>(running_.size());
  p.frames = frames_;
  p.seconds = Since(start_);
  const int left = n_ - out_.done - out_.failed;
  const double mean = ran_ended_ > 0 ? ran_seconds_ / ran_ended_ : 0.0;
  p.eta_seconds = mean * left / std::max(1, options_.jobs);
  progress_(p);
}

// The partial result to the caller after a take ends: at most once a second, and never
// more than a tenth of the batch's time (a summary of 10^5 takes takes a while).
void BatchRun::Checkpoint() {
  if (!options_.checkpoint) return;
  if (Since(last_checkpoint_) < std::max(1.0, 10.0 * checkpoint_cost_) && out_.done + out_.failed > 1) return;
  const auto t0 = Clock::now();
  out_.seconds = Since(start_);
  out_.own_seconds = own_;
  options_.checkpoint(out_);
  last_checkpoint_ = Clock::now();
  checkpoint_cost_ = Since(t0);
}

}  // namespace

TakeSummary SummaryOf(TakeRecord&& record) {
  TakeSummary summary;
  summary.take = std::move(record.take);
  summary.key = std::move(record.key);
  summary.status = std::move(record.status);
  summary.exit = std::move(record.exit);
  summary.error = std::move(record.error);
  summary.exit_code = record.exit_code;
  summary.wall_seconds = record.wall_seconds;
  summary.figures = std::move(record.figures);
  return summary;
}

Status RunBatch(const BatchManifest& manifest, const BatchRunOptions& options,
                const std::function<void(const BatchProgress&)>& progress, BatchResult* result) {
  BatchRun run(manifest, options, progress);
  return run.Run(result);
}

}  // namespace mocapsolve
