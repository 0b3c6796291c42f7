#include "batch/batch_summary.h"

#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/atomic_file.h"
#include "io/html_escape.h"
#include "io/json_writer.h"

namespace mocapsolve {
namespace {

std::string CsvCell(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return quoted + "\"";
}

std::string CsvNumber(double value) {
  if (std::isnan(value)) return "";
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

// The take's page relative to the batch folder ("02_05/view.html"), or "".
std::string ViewLink(const TakeSummary& r) { return r.figures.view.empty() ? "" : r.take + "/" + r.figures.view; }

// The same as a link that no name can turn into a script or another site.
std::string ViewUrl(const TakeSummary& r) { return r.figures.view.empty() ? "" : RelativeUrl({r.take, r.figures.view}); }

// A take that has not ended (a summary written while the batch runs) is not listed.
bool Ended(const TakeOutcome& outcome) { return !outcome.record.status.empty(); }

int Pending(const BatchResult& result) {
  return static_cast<int>(std::count_if(result.takes.begin(), result.takes.end(),
                                        [](const TakeOutcome& t) { return !Ended(t); }));
}

std::string HtmlNumber(double value, const char* format) {
  if (std::isnan(value)) return "";
  char text[32];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

}  // namespace

std::string FormatSummaryJson(const BatchResult& result, const std::string& version) {
  JsonObject root;
  root.Add("format", "mocapsolve.batch_summary").Add("version", 1).Add("program_version", version)
      .Add("takes_total", static_cast<int>(result.takes.size())).Add("done", result.done)
      .Add("failed", result.failed).Add("gate_failed", result.gate_failed).Add("pending", Pending(result))
      .Add("ran", result.ran).Add("skipped", result.skipped)
      .Add("seconds", result.seconds).Add("batch_own_seconds", result.own_seconds);
  // The takes' array appended last, one take at a time, into the text itself (a JsonObject
  // tree of 10^5 takes costs ~1 KB each, and copies the array's text three times).
  std::string text = root.ToString();
  text.pop_back();  // The closing '}'.
  text += ",\n  \"takes\": [";
  bool first = true;
  for (const TakeOutcome& outcome : result.takes) {
    if (!Ended(outcome)) continue;
    const TakeSummary& r = outcome.record;
    const TakeFigures& f = r.figures;
    std::vector<JsonObject> timings;
    for (const StageTime& t : f.timings) {
      JsonObject o;
      o.Add("stage", t.stage).Add("seconds", t.seconds);
      timings.push_back(o);
    }
    JsonObject o;
    o.Add("take", r.take).Add("status", r.status).Add("ran", outcome.ran).Add("exit", r.exit)
        .Add("exit_code", r.exit_code).Add("error", r.error).Add("frames", f.frames)
        .Add("wall_seconds", r.wall_seconds).Add("timings", timings).Add("naive_rms_mm", f.naive_rms_mm)
        .Add("repaired_rms_mm", f.repaired_rms_mm).Add("repaired_share", f.repaired_share)
        .Add("gate_pass", f.gate_pass < 0 ? JsonValue() : JsonValue(f.gate_pass == 1))
        .Add("vertex_error", f.vertex_error).Add("foot_skating_cm_per_s", f.foot_skating_cm_s)
        .Add("limb_mean_deg", f.limb_mean_deg).Add("limb_p95_deg", f.limb_p95_deg)
        .Add("penetration_cm", f.penetration_cm).Add("min_limb_vertices", f.min_limb_vertices)
        .Add("view", ViewLink(r).empty() ? JsonValue() : JsonValue(ViewLink(r))).Add("key", r.key);
    text += first ? "" : ", ";
    text += o.ToString(/*indent=*/false);
    first = false;
  }
  text += "]\n}\n";
  return text;
}

std::string FormatSummaryCsv(const BatchResult& result) {
  std::string csv =
      "take,status,ran,exit,exit_code,error,frames,wall_seconds,stage_seconds,naive_rms_mm,repaired_rms_mm,"
      "repaired_share,gate_pass,vertex_error,foot_skating_cm_per_s,limb_mean_deg,limb_p95_deg,penetration_cm,"
      "min_limb_vertices,view\n";
  for (const TakeOutcome& outcome : result.takes) {
    if (!Ended(outcome)) continue;
    const TakeSummary& r = outcome.record;
    const TakeFigures& f = r.figures;
    std::string stages;
    for (const StageTime& t : f.timings) stages += (stages.empty() ? "" : ";") + t.stage + "=" + CsvNumber(t.seconds);
    csv += CsvCell(r.take) + "," + r.status + "," + (outcome.ran ? "1" : "0") + "," + CsvCell(r.exit) + "," +
           std::to_string(r.exit_code) + "," + CsvCell(r.error) + "," + std::to_string(f.frames) + "," +
           CsvNumber(r.wall_seconds) + "," + CsvCell(stages) + "," + CsvNumber(f.naive_rms_mm) + "," +
           CsvNumber(f.repaired_rms_mm) + "," + CsvNumber(f.repaired_share) + "," +
           (f.gate_pass < 0 ? "" : f.gate_pass ? "1" : "0") + "," + CsvNumber(f.vertex_error) + "," +
           CsvNumber(f.foot_skating_cm_s) + "," + CsvNumber(f.limb_mean_deg) + "," + CsvNumber(f.limb_p95_deg) + "," +
           CsvNumber(f.penetration_cm) + "," + CsvNumber(f.min_limb_vertices) + "," + CsvCell(ViewLink(r)) + "\n";
  }
  return csv;
}

std::string FormatSummaryHtml(const BatchResult& result) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>mocapsolve batch</title>\n"
      "<style>body{font:14px system-ui,sans-serif;margin:1.5em}table{border-collapse:collapse}"
      "td,th{padding:3px 10px;border-bottom:1px solid #ddd;text-align:left}td.n{text-align:right}"
      ".failed,.gate_failed{color:#b00}</style></head><body>\n<h1>mocapsolve batch</h1>\n<p>" +
      std::to_string(result.done) + " done, " + std::to_string(result.failed) + " failed (" +
      std::to_string(result.gate_failed) + " of them at the quality gate), " + std::to_string(Pending(result)) +
      " pending of " + std::to_string(result.takes.size()) +
      " takes.</p>\n<table>\n<tr><th>take</th><th>status</th><th>frames</th><th>marker RMS repaired (mm)</th>"
      "<th>repaired share</th><th>gate</th><th>page</th><th>error</th></tr>\n";
  for (const TakeOutcome& outcome : result.takes) {
    if (!Ended(outcome)) continue;
    const TakeSummary& r = outcome.record;
    const TakeFigures& f = r.figures;
    const std::string link = ViewUrl(r);
    html += "<tr class=\"" + HtmlEscape(r.status) + "\"><td>" + HtmlEscape(r.take) + "</td><td>" + HtmlEscape(r.status) +
            "</td><td class=\"n\">" + std::to_string(f.frames) + "</td><td class=\"n\">" +
            HtmlNumber(f.repaired_rms_mm, "%.2f") + "</td><td class=\"n\">" +
            HtmlNumber(100.0 * f.repaired_share, "%.2f %%") + "</td><td>" +
            (f.gate_pass < 0 ? "" : f.gate_pass ? "pass" : "fail") + "</td><td>" +
            (link.empty() ? "" : "<a href=\"" + HtmlEscape(link) + "\">view</a>") + "</td><td>" + HtmlEscape(r.error) +
            "</td></tr>\n";
  }
  return html + "</table>\n</body></html>\n";
}

Status WriteBatchSummary(const std::string& out_dir, const BatchResult& result, const std::string& version,
                         const std::string& base) {
  // The JSON last: a batch killed at any instant that left a summary.json has left its .csv and
  // .html too, of this round or the one before.
  Status status = WriteFileAtomicallyNow(out_dir + "/" + base + ".csv", FormatSummaryCsv(result));
  if (status.ok()) status = WriteFileAtomicallyNow(out_dir + "/" + base + ".html", FormatSummaryHtml(result));
  return status.ok() ? WriteFileAtomicallyNow(out_dir + "/" + base + ".json", FormatSummaryJson(result, version)) : status;
}

Status CollectRecords(const std::string& out_dir, const BatchManifest* manifest, BatchResult* result) {
  std::vector<std::string> names;
  if (manifest != nullptr) {
    for (const BatchTake& take : manifest->takes) names.push_back(take.name);
  } else {
    DIR* dir = ::opendir(out_dir.c_str());
    if (dir == nullptr) return Status::Error(out_dir + ": cannot read the folder");
    while (const dirent* entry = ::readdir(dir)) {
      const std::string name = entry->d_name;
      if (name[0] == '.') continue;
      struct stat st;
      if (::stat(RecordPath(out_dir + "/" + name).c_str(), &st) == 0) names.push_back(name);
    }
    ::closedir(dir);
    std::sort(names.begin(), names.end());
    if (names.empty()) return Status::Error(out_dir + ": no take records (*/record.json) to merge");
  }
  BatchResult out;
  for (const std::string& name : names) {
    TakeOutcome outcome;
    TakeRecord r;
    const std::string path = RecordPath(out_dir + "/" + name);
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) {
      r.take = name;
      r.status = "missing";
      r.exit = "not run";
      r.exit_code = -1;
      r.error = "no record: the take has not run (or its shard was killed)";
    } else {
      Status status = ReadTakeRecord(path, &r);
      if (!status.ok()) return status;
    }
    outcome.record = SummaryOf(std::move(r));
    const std::string& status = outcome.record.status;
    (status == "done" ? out.done : out.failed) += 1;
    out.gate_failed += status == "gate_failed";
    ++out.skipped;
    out.takes.push_back(std::move(outcome));
  }
  *result = std::move(out);
  return Status::Ok();
}

Status ParseShard(const std::string& text, int* index, int* count) {
  *index = 0;
  *count = 1;
  if (text.empty()) return Status::Ok();
  int i = -1, n = -1;
  char rest = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &rest) != 2 || n < 1 || i < 0 || i >= n) {
    return Status::Error("--shard=" + text + ": expected i/n with 0 <= i < n");
  }
  *index = i;
  *count = n;
  return Status::Ok();
}

void KeepShard(int index, int count, BatchManifest* manifest) {
  std::vector<BatchTake> kept;
  for (size_t p = 0; p < manifest->takes.size(); ++p) {
    if (static_cast<int>(p % count) == index) kept.push_back(std::move(manifest->takes[p]));
  }
  manifest->takes = std::move(kept);
}

}  // namespace mocapsolve
