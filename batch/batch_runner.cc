#include "batch/batch_runner.h"

#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>

#include <dirent.h>

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

Status WriteText(const std::string& path, const std::string& text) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return Status::Error(path + ": cannot write the file");
  const bool ok = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  return std::fclose(file) == 0 && ok ? Status::Ok() : Status::Error(path + ": cannot write the file");
}

struct TakeState {
  TakeKey key;
  std::string config_path;
  double started = 0.0;  // Seconds since the epoch.
};

double Now() {
  struct timespec now;
  ::clock_gettime(CLOCK_REALTIME, &now);
  return now.tv_sec + 1e-9 * now.tv_nsec;
}

}  // namespace


Status RunBatch(const BatchManifest& manifest, const BatchRunOptions& options,
                const std::function<void(const BatchProgress&)>& progress, BatchResult* result) {
  const auto start = Clock::now();
  Status status = MakeFolders(options.out_dir);
  if (!status.ok()) return status;
  const char* tmp = std::getenv("TMPDIR");
  std::string temp_folder = std::string(tmp != nullptr && *tmp ? tmp : "/tmp") + "/mocapsolve-batch-XXXXXX";
  if (::mkdtemp(temp_folder.data()) == nullptr) {
    return Status::Error(temp_folder + ": cannot create a temporary folder for the takes' configs");
  }

  const int n = static_cast<int>(manifest.takes.size());
  BatchResult out;
  out.takes.resize(n);
  std::vector<TakeState> states(n);
  std::vector<WorkerJob> work(n);
  std::map<std::string, uint64_t> hash_cache;  // Shared files (subject, characters) hashed once.
  double own = 0.0;
  double ran_seconds = 0.0;
  int ran_ended = 0, running = 0;
  long frames = 0;

  auto take_dir = [&](int i) { return options.out_dir + "/" + manifest.takes[i].name; };
  auto report = [&]() {
    if (!progress) return;
    BatchProgress p;
    p.takes = n;
    p.done = out.done;
    p.failed = out.failed;
    p.skipped = out.skipped;
    p.running = running;
    p.frames = frames;
    p.seconds = Since(start);
    const int left = n - out.done - out.failed;
    const double mean = ran_ended > 0 ? ran_seconds / ran_ended : 0.0;
    p.eta_seconds = mean * left / std::max(1, options.jobs);
    progress(p);
  };
  // A take's record, once on disk, is read back for the summary at the end instead of being
  // kept: the batch then holds nothing per finished take, and stays flat in memory over
  // thousands of takes.
  std::vector<char> reread(n, 0);
  auto finish = [&](int i, TakeRecord record, bool ran, bool on_disk) {
    (record.status == "done" ? out.done : out.failed) += 1;
    (ran ? out.ran : out.skipped) += 1;
    out.takes[i].ran = ran;
    reread[i] = on_disk;
    if (!on_disk) out.takes[i].record = std::move(record);
    // Free the take's key (swapped out: assigning empty strings would keep their capacity).
    TakeState released;
    std::swap(states[i], released);
    work[i].argv = std::vector<std::string>();
  };
  auto failed_record = [&](int i, const std::string& error) {
    TakeRecord record;
    record.take = manifest.takes[i].name;
    record.program_version = options.version;
    record.status = "failed";
    record.exit = "1";
    record.exit_code = 1;
    record.error = error;
    return record;
  };

  for (int i = 0; i < n; ++i) {
    const BatchTake& take = manifest.takes[i];
    work[i].label = take.name;
  }

  WorkerCallbacks callbacks;
  // The takes' files (subject, records, reports) are read by every take: not recorded as the
  // batch's inputs (the workers guard their own), so the batch stays flat in memory.
  callbacks.on_start = [&](int i) -> bool {
    FileTransaction::UntrackedReads untracked;
    const auto t0 = Clock::now();
    const BatchTake& take = manifest.takes[i];
    const std::string dir = take_dir(i);
    TakeState& state = states[i];
    Status s = ComputeTakeKey(take, options.version, &state.key, &hash_cache);
    if (!s.ok()) {
      // An unreadable input: failed before any worker; no record (nothing to resume).
      finish(i, failed_record(i, s.message()), true, false);
      own += Since(t0);
      report();
      return false;
    }
    const std::string key = HexHash(state.key.key);
    TakeRecord old;
    const bool has_record = FileExists(RecordPath(dir)) && ReadTakeRecord(RecordPath(dir), &old).ok();
    if (has_record && !options.force && old.key == key) {
      bool outputs = old.status == "done";
      for (const std::string& file : old.outputs) outputs = outputs && FileExists(dir + "/" + file);
      if ((old.status == "done" && outputs) || (old.status == "failed" && !options.retry_failed)) {
        finish(i, std::move(old), false, true);
        own += Since(t0);
        report();
        return false;
      }
    }
    if (has_record) {
      // The record first: from here the folder's outputs are not claimed by any key.
      ::unlink(RecordPath(dir).c_str());
      for (const std::string& file : old.outputs) {
        if (file.find('/') == std::string::npos) ::unlink((dir + "/" + file).c_str());
      }
    }
    state.config_path = temp_folder + "/" + take.name + ".json";
    s = WriteText(state.config_path, state.key.given_json + "\n");
    if (!s.ok()) {
      finish(i, failed_record(i, s.message()), true, false);
      own += Since(t0);
      report();
      return false;
    }
    std::vector<std::string>& argv = work[i].argv;
    argv = {options.executable, "pipeline", "--quiet", "--subject=" + take.subject, "--markers=" + take.markers,
            "--out_dir=" + dir, "--config=" + state.config_path};
    const bool threads_given = std::any_of(take.given.begin(), take.given.end(),
                                           [](const auto& option) { return option.first == "num_threads"; });
    if (options.take_threads > 0 && !threads_given) {
      argv.push_back("--num_threads=" + std::to_string(options.take_threads));
    }
    if (!take.characters.empty()) {
      std::string list;
      for (const std::string& c : take.characters) list += (list.empty() ? "" : ",") + c;
      argv.push_back("--character=" + list);
    }
    state.started = Now();
    ++running;
    own += Since(t0);
    return true;
  };
  callbacks.on_done = [&](int i, const WorkerResult& worker) {
    FileTransaction::UntrackedReads untracked;
    const auto t0 = Clock::now();
    --running;
    const std::string dir = take_dir(i);
    TakeState& state = states[i];
    ::unlink(state.config_path.c_str());
    TakeRecord record;
    record.take = manifest.takes[i].name;
    record.key = HexHash(state.key.key);
    record.program_version = options.version;
    record.inputs = state.key.inputs;
    record.options_json = state.key.options_json;
    record.given_json = state.key.given_json;
    record.exit = worker.ExitName();
    record.exit_code = worker.exit_code;
    record.wall_seconds = worker.seconds;
    record.status = worker.ok() ? "done" : "failed";
    if (!worker.ok()) {
      record.error = worker.last_line.empty() ? "the worker ended with " + record.exit : worker.last_line;
      if (worker.timed_out) {
        char text[64];
        std::snprintf(text, sizeof(text), "timed out after %.3g s", options.limits.timeout_seconds);
        record.error = std::string(text) + (worker.last_line.empty() ? "" : ": " + worker.last_line);
      }
    }
    const bool has_outputs = worker.started && worker.signal == 0 && !worker.timed_out &&
                             (worker.exit_code == 0 || worker.exit_code == 3);
    if (has_outputs) {
      Status s = TakeFiguresFromReport(dir + "/report.json", &record.figures);
      if (!s.ok() && worker.ok()) {
        record.status = "failed";
        record.error = s.message();
      }
      // Less a second: file systems with coarse timestamps.
      record.outputs = FolderFiles(dir, state.started - 1.0);
    }
    // A worker that produced nothing: its folder is made for the record alone.
    Status s = MakeFolders(dir);
    if (s.ok()) s = WriteTakeRecord(dir, record);
    if (!s.ok()) {
      record.status = "failed";
      record.error += (record.error.empty() ? "" : "; ") + std::string("cannot write the record: ") + s.message();
    }
    frames += record.figures.frames;
    ran_seconds += worker.seconds;
    ++ran_ended;
    finish(i, std::move(record), true, s.ok());
    own += Since(t0);
    report();
  };
  callbacks.on_tick = report;
  RunWorkers(work, options.jobs, options.limits, callbacks);
  ::rmdir(temp_folder.c_str());
  FileTransaction::UntrackedReads untracked;
  for (int i = 0; i < n; ++i) {
    if (!reread[i]) continue;
    TakeRecord& record = out.takes[i].record;
    if (!ReadTakeRecord(RecordPath(take_dir(i)), &record).ok()) {
      record = failed_record(i, RecordPath(take_dir(i)) + ": the take's record vanished during the batch");
    }
  }
  out.seconds = Since(start);
  out.own_seconds = own;
  report();
  *result = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
