// A batch's summary: DIR/summary.json and DIR/summary.csv list every take of the manifest
// (the ones skipped as already done or failed too, from their records): status, exit
// ("0", "3" gate failed, "1" bad input, a signal name, "timeout"), exit code, the one-line
// error, frames, wall time, per-stage seconds, marker RMS (naive / repaired, mm), repaired
// samples share, quality gate pass, retarget vertex error (fraction of height) and foot
// skating (cm/s). The CSV has one row per take with the stages as "stage=seconds;..." in
// one column; empty cells for figures a take did not produce. Each take's page
// ("<take>/view.html", when the pipeline wrote one) is a field of both, and
// DIR/summary.html is an index: one table row per take with a link to its page (a
// relative URL, RelativeUrl in io/html_escape.h: no take name makes it a script).
// Status is "done", "gate_failed" (exit 3: ran, outputs kept), "failed" or, from
// --merge, "missing". A summary written while the batch runs lists the takes that ended
// and counts the others as "pending".
#ifndef MOCAPSOLVE_BATCH_BATCH_SUMMARY_H_
#define MOCAPSOLVE_BATCH_BATCH_SUMMARY_H_

#include <string>
#include <vector>

#include "batch/batch_runner.h"
#include "kinematics/status.h"

namespace mocapsolve {

std::string FormatSummaryJson(const BatchResult& result, const std::string& version);
std::string FormatSummaryCsv(const BatchResult& result);
std::string FormatSummaryHtml(const BatchResult& result);

// The three files, each atomically and at once (not at the command's end), the JSON last:
// DIR/<base>.json, DIR/<base>.csv and DIR/<base>.html.
Status WriteBatchSummary(const std::string& out_dir, const BatchResult& result, const std::string& version,
                         const std::string& base = "summary");

// The result of the takes' records alone (batch --merge, after the shards of a batch ran
// apart): with a manifest, its takes in order, a take without a record listed as
// "missing"; without one (nullptr), every DIR/*/record.json in name order.
Status CollectRecords(const std::string& out_dir, const BatchManifest* manifest, BatchResult* result);

// Shard `index` of `count` (0 <= index < count): the takes whose manifest position p has
// p % count == index. "i/n" parsed by ParseShard; "" = the whole batch (0/1).
Status ParseShard(const std::string& text, int* index, int* count);
void KeepShard(int index, int count, BatchManifest* manifest);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_BATCH_BATCH_SUMMARY_H_
