#include "tasks/evaluate_retarget_task.h"

#include <cstdio>
#include <sstream>

#include "io/motion_file.h"
#include "pipeline/retarget_quality_report.h"
#include "tasks/console_text.h"
#include "tasks/retarget_task.h"

namespace mocapsolve {
namespace {

std::string Figure(double value, const char* format) {
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return std::isnan(value) ? "-" : text;
}

}  // namespace

std::vector<std::string> SplitCharacterList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

Status RunEvaluateRetarget(const EvaluateRetargetInputs& inputs, const RetargetSettings& retarget,
                           const QualityGate& gate, const std::function<void(int done, int total)>& progress,
                           EvaluateRetargetResult* result) {
  *result = EvaluateRetargetResult();
  if (inputs.source.empty()) return Status::Error("--source: required with --method=retarget");
  if (inputs.characters.empty()) return Status::Error("--target: one or more characters (A.glb,B.glb) required");
  std::string error;
  if (!gate.IsValid(&error)) return Status::Error(error);
  result->table = "character        limb mean  limb p95  align  skate cm/s  pen cm  self cm  fewest limb vertices"
                  "       vertex err  verdict\n";
  result->table_csv = "character,limb_mean_deg,limb_p95_deg,alignment_deg,foot_skate_cm_per_s,penetration_cm,"
                      "self_joint_error_max_cm,min_limb_vertices,least_covered_limb,"
                      "mean_vertex_error_fraction_of_height,pass,pelvis_orientation_mean_deg,pelvis_orientation_p95_deg,"
                      "chest_orientation_mean_deg,chest_orientation_p95_deg\n";
  std::vector<JsonObject> rows;
  for (size_t i = 0; i < inputs.characters.size(); ++i) {
    RetargetInputs one;
    one.source = inputs.source;
    one.target = inputs.characters[i];
    one.skeleton = inputs.skeleton;
    one.amc_fps = inputs.amc_fps;
    one.max_frames = inputs.max_frames;
    RetargetConfig config;
    config.retarget = retarget;
    config.gate = gate;
    RetargetTaskResult task;
    Status status = RunRetarget(one, config, nullptr, &task);
    if (!status.ok()) return status;
    EvaluateRetargetRow row;
    row.character = FileStem(one.target);
    row.quality = task.retarget.quality;
    CheckRetargetQuality(gate, row.quality, row.character, &row.verdict);
    row.mean_vertex_error = task.retarget.clip.mean_position_error;
    row.ms_per_frame = 1e3 * task.retarget.clip.solve_seconds / std::max(1, task.source_motion.num_frames());
    const RetargetQuality& q = row.quality;
    AppendF(&result->table, "%-16s %9s %9s %6s %11s %7s %8s %6d %-15s %10.4f  %s\n", row.character.c_str(),
            Figure(q.limb_mean_deg, "%.1f").c_str(), Figure(q.limb_p95_deg, "%.1f").c_str(),
            Figure(q.alignment_deg, "%.1f").c_str(), Figure(q.foot_skate_cm_s, "%.2f").c_str(),
            Figure(q.penetration_cm, "%.1f").c_str(),
            Figure(q.self_joint_error_max_cm, "%.3f").c_str(), q.min_limb_vertices,
            q.least_covered_limb.empty() ? "-" : q.least_covered_limb.c_str(), row.mean_vertex_error,
            row.verdict.pass ? "pass" : "FAIL");
    AppendF(&result->table_csv, "%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%s,%.6g,%s,%.6g,%.6g,%.6g,%.6g\n",
            row.character.c_str(), q.limb_mean_deg, q.limb_p95_deg, q.alignment_deg, q.foot_skate_cm_s,
            q.penetration_cm, q.self_joint_error_max_cm, q.min_limb_vertices, q.least_covered_limb.c_str(),
            row.mean_vertex_error, row.verdict.pass ? "true" : "false", q.pelvis_orientation_mean_deg,
            q.pelvis_orientation_p95_deg, q.chest_orientation_mean_deg, q.chest_orientation_p95_deg);
    JsonObject o;
    o.Add("character", row.character).Add("file", one.target).Add("frames", task.source_motion.num_frames())
        .Add("mean_vertex_error_fraction_of_height", row.mean_vertex_error).Add("ms_per_frame", row.ms_per_frame)
        .Add("quality", RetargetQualityJson(q, row.verdict.failures));
    rows.push_back(o);
    result->rows.push_back(std::move(row));
    if (progress) progress(static_cast<int>(i) + 1, static_cast<int>(inputs.characters.size()));
  }
  for (const EvaluateRetargetRow& row : result->rows) {
    for (const std::string& failure : row.verdict.failures) result->table += "  " + failure + "\n";
  }
  result->report.Add("method", "retarget").Add("source", inputs.source).Add("characters", rows);
  return Status::Ok();
}

}  // namespace mocapsolve
