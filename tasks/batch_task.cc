#include "tasks/batch_task.h"

#include <algorithm>
#include <thread>

#include "batch/batch_summary.h"
#include "batch/manifest.h"
#include "batch/output_guard.h"
#include "batch/worker_process.h"
#include "io/atomic_file.h"

namespace mocapsolve {
namespace {

Status CheckInputs(const BatchInputs& inputs) {
  if (inputs.settings.merge && inputs.out_dir.empty()) return Status::Error("--merge needs --out_dir");
  if (inputs.settings.merge && inputs.manifest.empty()) return Status::Ok();
  if (inputs.manifest.empty() == inputs.markers_glob.empty()) {
    return Status::Error("give either --manifest or --markers_glob (with --subject)");
  }
  if (inputs.out_dir.empty() && inputs.write_manifest.empty()) return Status::Error("--out_dir is required");
  Status status = BatchSettingOptions().Validate(inputs.settings);
  if (!status.ok()) return status;
  if (!inputs.manifest.empty() && (!inputs.subject.empty() || !inputs.characters.empty())) {
    return Status::Error("--subject and --character go with --markers_glob; a manifest names its own");
  }
  return Status::Ok();
}

// The manifest, checked against the pipeline's own options (the keys it may hold).
Status LoadManifest(const BatchInputs& inputs, BatchOptions* pipeline_options, BatchManifest* manifest) {
  std::string config;
  Status status = RunAndCapture({inputs.executable, "pipeline", "--print_config"}, &config);
  if (status.ok()) status = ParsePipelineOptions(config, pipeline_options);
  if (!status.ok()) return status;
  if (!inputs.manifest.empty()) {
    status = ReadManifest(inputs.manifest, *pipeline_options, manifest);
  } else {
    status = ManifestFromGlob(inputs.markers_glob, inputs.subject, inputs.characters, *pipeline_options, manifest);
  }
  if (!status.ok() || inputs.pipeline_options.empty()) return status;
  JsonNode given;
  status = ParseJson(inputs.pipeline_options, "the batch's pipeline options", &given);
  if (status.ok() && !given.is_object()) status = Status::Error("the batch's pipeline options: expected an object");
  if (status.ok()) status = SetDefaultOptions(given.members, manifest);
  return status;
}

Status Merge(const BatchInputs& inputs, const BatchManifest* manifest, BatchTaskResult* out) {
  out->kind = BatchTaskResult::Kind::kMerged;
  out->summary_base = "summary";
  Status status = Status::Ok();
  if (manifest != nullptr) {
    status = CheckBatchOutputs(*manifest, inputs.out_dir, BatchOutputs(inputs.out_dir, "summary", "", ""));
  }
  if (status.ok()) status = CollectRecords(inputs.out_dir, manifest, &out->result);
  if (status.ok()) status = WriteBatchSummary(inputs.out_dir, out->result, inputs.version);
  return status;
}

}  // namespace

Status RunBatchTask(const BatchInputs& inputs, const std::function<void(const BatchProgress&)>& progress,
                    BatchTaskResult* out) {
  *out = BatchTaskResult();
  Status status = CheckInputs(inputs);
  if (!status.ok()) return status;
  if (inputs.settings.merge && inputs.manifest.empty()) return Merge(inputs, nullptr, out);
  BatchOptions pipeline_options;
  BatchManifest manifest;
  status = LoadManifest(inputs, &pipeline_options, &manifest);
  if (!status.ok()) return status;
  if (inputs.settings.merge) return Merge(inputs, &manifest, out);

  status = ParseShard(inputs.settings.shard, &out->shard, &out->shards);
  if (!status.ok()) return status;
  const std::string shard_name =
      out->shards == 1 ? "" : ".shard" + std::to_string(out->shard) + "of" + std::to_string(out->shards);
  out->summary_base = "summary" + shard_name;
  BatchRunOptions options;
  options.executable = inputs.executable;
  options.version = inputs.version;
  options.work_dir = inputs.out_dir.empty() ? "" : inputs.out_dir + "/.batch-work" + shard_name;
  // Every output against every input, before anything is written.
  status = CheckBatchOutputs(manifest, inputs.out_dir,
                             BatchOutputs(inputs.out_dir, out->summary_base, options.work_dir, inputs.write_manifest));
  if (!status.ok()) return status;
  if (!inputs.write_manifest.empty()) {
    // At once, not when the batch ends: a batch killed later still leaves its manifest.
    status = WriteFileAtomicallyNow(inputs.write_manifest, FormatManifest(manifest, pipeline_options));
    if (!status.ok()) return status;
    if (inputs.out_dir.empty()) {
      out->kind = BatchTaskResult::Kind::kManifestOnly;
      out->manifest_takes = static_cast<int>(manifest.takes.size());
      return Status::Ok();
    }
  }
  KeepShard(out->shard, out->shards, &manifest);
  if (manifest.takes.empty()) {
    out->kind = BatchTaskResult::Kind::kEmptyShard;
    return Status::Ok();
  }
  options.out_dir = inputs.out_dir;
  const int cores = std::max(1u, std::thread::hardware_concurrency());
  options.jobs = inputs.settings.jobs > 0 ? inputs.settings.jobs : cores;
  options.take_threads = inputs.settings.take_threads > 0 ? inputs.settings.take_threads : std::max(1, cores / options.jobs);
  options.limits.timeout_seconds = inputs.settings.take_timeout;
  options.limits.memory_mb = inputs.settings.take_memory_mb;
  options.force = inputs.settings.force;
  options.retry_failed = inputs.settings.retry_failed;
  const std::string& summary_base = out->summary_base;
  options.checkpoint = [&options, &summary_base, &inputs](const BatchResult& partial) {
    // A summary as takes end: a killed batch leaves one. (A failed write is retried next time.)
    (void)WriteBatchSummary(options.out_dir, partial, inputs.version, summary_base);
  };
  status = RunBatch(manifest, options, progress, &out->result);
  if (!status.ok()) return status;
  return WriteBatchSummary(options.out_dir, out->result, inputs.version, summary_base);
}

}  // namespace mocapsolve
