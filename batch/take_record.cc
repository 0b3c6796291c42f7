#include "batch/take_record.h"

#include "io/atomic_file.h"
#include "io/json_reader.h"
#include "io/json_writer.h"

namespace mocapsolve {
namespace {

double Number(const JsonNode* node) {
  return node != nullptr && node->is_number() ? node->number : TakeFigures::kNone;
}

std::string String(const JsonNode* node) { return node != nullptr && node->is_string() ? node->string : ""; }

}  // namespace

Status TakeFiguresFromReport(const std::string& report_path, TakeFigures* figures) {
  JsonNode root;
  Status status = ReadJsonFile(report_path, &root);
  if (!status.ok()) return status;
  TakeFigures f;
  f.frames = static_cast<int>(std::isnan(Number(root.Find("frames"))) ? 0 : Number(root.Find("frames")));
  if (const JsonNode* timings = root.Find("timings"); timings != nullptr && timings->is_array()) {
    for (const JsonNode& t : timings->items) f.timings.push_back({String(t.Find("stage")), Number(t.Find("seconds"))});
  }
  if (const JsonNode* gate = root.Find("quality_gate")) {
    f.naive_rms_mm = Number(gate->Find("naive_rms_mm"));
    f.repaired_rms_mm = Number(gate->Find("repaired_rms_mm"));
    f.repaired_share = Number(gate->Find("repaired_share"));
    if (const JsonNode* pass = gate->Find("pass"); pass != nullptr && pass->is_bool()) f.gate_pass = pass->boolean;
  }
  if (const JsonNode* characters = root.Find("characters"); characters != nullptr && characters->is_array() &&
                                                            !characters->items.empty()) {
    double error = 0.0, skating = 0.0;
    for (const JsonNode& c : characters->items) {
      error += Number(c.Find("mean_vertex_error_fraction_of_height"));
      skating += Number(c.Find("result_foot_skating_cm_per_s"));
    }
    f.vertex_error = error / characters->items.size();
    f.foot_skating_cm_s = skating / characters->items.size();
  }
  f.view = String(root.Find("view"));
  *figures = std::move(f);
  return Status::Ok();
}

std::string RecordPath(const std::string& take_dir) { return take_dir + "/record.json"; }

std::string FormatTakeRecord(const TakeRecord& r) {
  std::vector<JsonObject> inputs;
  for (const KeyInput& input : r.inputs) {
    JsonObject o;
    o.Add("role", input.role).Add("path", input.path).Add("hash", HexHash(input.hash));
    inputs.push_back(o);
  }
  std::vector<JsonObject> timings;
  for (const StageTime& t : r.figures.timings) {
    JsonObject o;
    o.Add("stage", t.stage).Add("seconds", t.seconds);
    timings.push_back(o);
  }
  std::vector<JsonValue> outputs(r.outputs.begin(), r.outputs.end());
  const TakeFigures& f = r.figures;
  JsonObject o;
  o.Add("format", "mocapsolve.batch_record").Add("version", 1).Add("take", r.take).Add("key", r.key)
      .Add("program_version", r.program_version).Add("inputs", inputs)
      .Add("options", JsonValue::Raw(r.options_json.empty() ? "{}" : r.options_json))
      .Add("given_options", JsonValue::Raw(r.given_json.empty() ? "{}" : r.given_json))
      .Add("status", r.status).Add("exit", r.exit).Add("exit_code", r.exit_code).Add("error", r.error)
      .Add("frames", f.frames).Add("wall_seconds", r.wall_seconds).Add("timings", timings)
      .Add("naive_rms_mm", f.naive_rms_mm).Add("repaired_rms_mm", f.repaired_rms_mm)
      .Add("repaired_share", f.repaired_share)
      .Add("gate_pass", f.gate_pass < 0 ? JsonValue() : JsonValue(f.gate_pass == 1))
      .Add("vertex_error", f.vertex_error).Add("foot_skating_cm_per_s", f.foot_skating_cm_s)
      .Add("view", f.view.empty() ? JsonValue() : JsonValue(f.view)).Add("outputs", outputs);
  return o.ToString() + "\n";
}

Status WriteTakeRecord(const std::string& take_dir, const TakeRecord& record) {
  return WriteFileAtomicallyNow(RecordPath(take_dir), FormatTakeRecord(record));
}

Status ReadTakeRecord(const std::string& path, TakeRecord* record) {
  JsonNode root;
  Status status = ReadJsonFile(path, &root);
  if (!status.ok()) return status;
  if (!root.is_object() || String(root.Find("format")) != "mocapsolve.batch_record") {
    return Status::Error(path + ": not a batch record");
  }
  TakeRecord r;
  r.take = String(root.Find("take"));
  r.key = String(root.Find("key"));
  r.program_version = String(root.Find("program_version"));
  r.status = String(root.Find("status"));
  r.exit = String(root.Find("exit"));
  const double code = Number(root.Find("exit_code"));
  r.exit_code = std::isnan(code) ? -1 : static_cast<int>(code);
  r.error = String(root.Find("error"));
  const double wall = Number(root.Find("wall_seconds"));
  r.wall_seconds = std::isnan(wall) ? 0.0 : wall;
  if (const JsonNode* inputs = root.Find("inputs"); inputs != nullptr && inputs->is_array()) {
    for (const JsonNode& i : inputs->items) {
      KeyInput input;
      input.role = String(i.Find("role"));
      input.path = String(i.Find("path"));
      input.hash = std::strtoull(String(i.Find("hash")).c_str(), nullptr, 16);
      r.inputs.push_back(input);
    }
  }
  TakeFigures& f = r.figures;
  const double frames = Number(root.Find("frames"));
  f.frames = std::isnan(frames) ? 0 : static_cast<int>(frames);
  if (const JsonNode* timings = root.Find("timings"); timings != nullptr && timings->is_array()) {
    for (const JsonNode& t : timings->items) f.timings.push_back({String(t.Find("stage")), Number(t.Find("seconds"))});
  }
  f.naive_rms_mm = Number(root.Find("naive_rms_mm"));
  f.repaired_rms_mm = Number(root.Find("repaired_rms_mm"));
  f.repaired_share = Number(root.Find("repaired_share"));
  if (const JsonNode* pass = root.Find("gate_pass"); pass != nullptr && pass->is_bool()) f.gate_pass = pass->boolean;
  f.vertex_error = Number(root.Find("vertex_error"));
  f.foot_skating_cm_s = Number(root.Find("foot_skating_cm_per_s"));
  f.view = String(root.Find("view"));
  if (const JsonNode* outputs = root.Find("outputs"); outputs != nullptr && outputs->is_array()) {
    for (const JsonNode& o : outputs->items) r.outputs.push_back(String(&o));
  }
  *record = std::move(r);
  return Status::Ok();
}

}  // namespace mocapsolve
