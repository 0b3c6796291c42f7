// mocapsolve batch: `pipeline` over many takes, each in its own worker process, resumable
// (batch/batch_runner.h); the summary of every take in DIR/summary.json and .csv.
#include <cstdio>
#include <cstdlib>
#include <string>

#include <gflags/gflags.h>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/progress.h"
#include "apps/config_flags.h"
#include "apps/delivery_flags.h"
#include "apps/option_flags.h"
#include "batch/worker_process.h"
#include "settings/take_settings.h"
#include "tasks/batch_task.h"


namespace mocapsolve {
namespace {

// `shard`, or the Slurm job array's task ("" = the whole batch).
std::string ShardOrSlurm(const std::string& shard) {
  std::string text = shard;
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* tasks = std::getenv("SLURM_ARRAY_TASK_COUNT");
  if (text.empty() && id != nullptr && tasks != nullptr) {
    const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
    text = std::to_string(std::atoi(id) - (min != nullptr ? std::atoi(min) : 0)) + "/" + tasks;
  }
  return text;
}

void PrintFailures(const BatchResult& result) {
  for (const TakeOutcome& t : result.takes) {
    if (t.record.status == "done" || t.record.status.empty()) continue;
    std::printf("  %s: %s (exit %s): %s\n", t.record.take.c_str(), t.record.status.c_str(), t.record.exit.c_str(),
                t.record.error.c_str());
  }
}

Status RunBatchCommand(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  BatchInputs inputs;
  inputs.manifest = Files().manifest;
  inputs.markers_glob = Files().markers_glob;
  inputs.subject = Files().subject;
  inputs.characters = SplitCommaList(Files().character);
  inputs.out_dir = Files().out_dir;
  ClipDelivery delivery;  // Checked here: a malformed range is the batch's error, not every take's.
  Status status = ClipDeliveryFromFlags(&delivery);
  if (!status.ok()) return status;
  inputs.pipeline_options = GivenFlagsJson(DeliverySettingOptions().Names() + ",label");
  inputs.write_manifest = Files().write_manifest;
  ReadOptionFlags(BatchSettingOptions(), &inputs.settings);
  inputs.settings.shard = ShardOrSlurm(inputs.settings.shard);
  inputs.executable = SelfExecutable();
  inputs.version = Version();
  ProgressLine line(Console().quiet);  // In place on a terminal, a line every few seconds in a log.
  BatchTaskResult task;
  status = RunBatchTask(inputs, [&line](const BatchProgress& p) {
    const bool last = p.done + p.failed == p.takes && p.running == 0;
    if (!line.Due(last)) return;
    char text[256];
    std::snprintf(text, sizeof(text), "batch: %d/%d takes: %d done, %d failed, %d running, %d skipped; %.0f "
                  "frames/s, ETA %.0f s", p.done + p.failed, p.takes, p.done, p.failed, p.running, p.skipped,
                  p.seconds > 0 ? p.frames / p.seconds : 0.0, p.eta_seconds);
    line.Show(text, last);
  }, &task);
  if (!status.ok()) return status;
  const BatchResult& result = task.result;
  switch (task.kind) {
    case BatchTaskResult::Kind::kManifestOnly:
      std::printf("wrote %s (%d takes)\n", Files().write_manifest.c_str(), task.manifest_takes);
      return Status::Ok();
    case BatchTaskResult::Kind::kEmptyShard:
      std::printf("batch: shard %d/%d has no takes\n", task.shard, task.shards);
      return Status::Ok();
    case BatchTaskResult::Kind::kMerged:
      std::printf("merged %zu %s: %d done, %d failed%s\n", result.takes.size(),
                  Files().manifest.empty() ? "take records" : "takes", result.done, result.failed,
                  Files().manifest.empty() ? "" : " or missing");
      break;
    case BatchTaskResult::Kind::kRan:
      std::printf("batch: %zu takes in %.2f s: %d done, %d failed (%d ran, %d skipped as unchanged); %d failed at "
                  "the quality gate; batch's own work %.1f ms\n", result.takes.size(), result.seconds, result.done,
                  result.failed, result.ran, result.skipped, result.gate_failed, 1000.0 * result.own_seconds);
      break;
  }
  PrintFailures(result);
  if (task.kind == BatchTaskResult::Kind::kRan) {
    std::printf("wrote %s/%s.json and .csv\n", Files().out_dir.c_str(), task.summary_base.c_str());
  }
  if (result.failed > 0) SetExitCodeOnSuccess(2);
  return Status::Ok();
}

}  // namespace

extern const Command kBatchCommand = {
    "batch", "many takes through pipeline, each in its own process, resumable",
    "mocapsolve batch --manifest=M.json --out_dir=DIR [--jobs=N] [--take_timeout=S] [--take_memory_mb=MB]\n"
    "                 [--take_threads=T] [--force | --retry_failed] [--shard=i/n]\n"
    "       mocapsolve batch --merge --out_dir=DIR [--manifest=M.json]\n"
    "       mocapsolve batch --markers_glob='takes/*.c3d' --subject=S.json|auto [--character=C.glb] --out_dir=DIR\n"
    "                 [--write_manifest=M.json]\n\n"
    "Runs `mocapsolve pipeline` on every take of the manifest, each in its own worker process\n"
    "(a crash, timeout or out-of-memory in one take does not stop the others), into\n"
    "DIR/<take>/. A finished take's DIR/<take>/record.json keeps a key of its input files'\n"
    "contents, options and program version: a re-run skips the takes whose key matches\n"
    "(and whose outputs exist), redoes the changed ones, and redoes failed ones only with\n"
    "--retry_failed. DIR/summary.json and DIR/summary.csv list every take (status, exit,\n"
    "error line, frames, timings, marker RMS, repaired share, gate, retarget error, foot\n"
    "skating, the take's view.html); DIR/summary.html links every take's page. The summaries\n"
    "are rewritten as takes end (about once a second), so killing the batch loses at most\n"
    "the takes in flight and leaves a summary of the others; --write_manifest is written at\n"
    "the start. The takes' config files live in DIR/.batch-work, emptied at each start.\n"
    "Take status: done; gate_failed (the take ran and its outputs are written, but its quality\n"
    "gate failed: pipeline exit 3); failed (crash, timeout, bad input; also a take whose\n"
    "markers, subject or character file is missing, unreadable or not a regular file: the\n"
    "other takes still run).\n"
    "With --markers_glob a take is named after its file without extension; files of the same\n"
    "name in different folders are all named <folder>_<name> (e.g. day1/walk.c3d and\n"
    "day2/walk.c3d: day1_walk, day2_walk).\n"
    "Take names must be plain folder names: at most 255 bytes, no '/', no control\n"
    "character, not starting with '.', not summary.json/.csv/.html, summary.shard* or the\n"
    "manifest's own file name. No output may be an input (compared by file identity): the\n"
    "batch refuses before writing anything.\n"
    "A batch split over machines (--shard=i/n, by default from a Slurm job array; see\n"
    "scripts/slurm/submit.sh) writes DIR/summary.shard<i>of<n>.json; --merge then builds\n"
    "DIR/summary.json from the takes' records.\n"
    "--subject=auto (a manifest's \"subject\": \"auto\"): each take's pipeline fits its own subject\n"
    "(pipeline --subject=auto; one fit per take) into DIR/<take>/subject.json; the fit options\n"
    "(fit_max_frames, check, ...) go in a manifest's defaults.\n"
    "--formats, --frames, --seconds, --out_fps and --label (raw takes: labelled first), when\n"
    "given, are every take's (over the manifest's defaults; a take's own value still wins).\n"
    "Exit code: 0 every take done, 2 some failed or gate_failed, 1 bad manifest or flags\n"
    "(its form: JSON, keys, types, names) or an output that is an input.",
    __FILE__, RunBatchCommand,
    {SharedOptions("subject,character,out_dir,manifest,markers_glob,write_manifest"),
     BatchSettingOptions().options(), DeliverySettingOptions().options(), TakeSettingOptions().Only("label").options()}};

}  // namespace mocapsolve
