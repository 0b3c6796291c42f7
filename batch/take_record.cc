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

// The worst character's retarget quality ("quality" of each character; NaN figures skipped).
void WorstRetargetQuality(const JsonNode& characters, TakeFigures* f) {
  auto worst = [](double* into, double value, bool larger) {
    if (std::isnan(value)) return;
    if (std::isnan(*into) || (larger ? value > *into : value < *into)) *into = value;
  };
  for (const JsonNode& c : characters.items) {
    const JsonNode* q = c.Find("quality");
    if (q == nullptr) continue;
    worst(&f->limb_mean_deg, Number(q->Find("limb_mean_deg")), true);
    worst(&f->limb_p95_deg, Number(q->Find("limb_p95_deg")), true);
    worst(&f->penetration_cm, Number(q->Find("penetration_cm")), true);
    if (const JsonNode* limb = q->Find("least_covered_limb"); limb != nullptr && !String(limb).empty()) {
      worst(&f->min_limb_vertices, Number(q->Find("min_limb_vertices")), false);
    }
  }
}

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
    WorstRetargetQuality(*characters, &f);
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
      .Add("limb_mean_deg", f.limb_mean_deg).Add("limb_p95_deg", f.limb_p95_deg)
      .Add("penetration_cm", f.penetration_cm).Add("min_limb_vertices", f.min_limb_vertices)
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
  f.limb_mean_deg = Number(root.Find("limb_mean_deg"));
  f.limb_p95_deg = Number(root.Find("limb_p95_deg"));
  f.penetration_cm = Number(root.Find("penetration_cm"));
  f.min_limb_vertices = Number(root.Find("min_limb_vertices"));
  f.view = String(root.Find("view"));
  if (const JsonNode* outputs = root.Find("outputs"); outputs != nullptr && outputs->is_array()) {
    for (const JsonNode& o : outputs->items) r.outputs.push_back(String(&o));
  }
  *record = std::move(r);
  return Status::Ok();
}

}  // namespace mocapsolve
