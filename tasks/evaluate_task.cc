#include "tasks/evaluate_task.h"

#include <algorithm>
#include <cstdio>

#include "settings/method_settings.h"
#include "tasks/leave_one_out_protocol.h"
#include "tasks/repair_task.h"

namespace mocapsolve {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

Status LeaveOneOut(const MarkerTake& evaluated, const EvaluateConfig& config,
                   const std::function<void(int, int)>& progress, EvaluateResult* result) {
  // The protocol decides the subject and the scored frames (leave_one_out_protocol.h).
  MarkerTake take;
  JsonObject protocol;
  Status status = LeaveOneOutProtocolTake(evaluated, config.evaluate.protocol, config.solver, config.fit, &take,
                                          &protocol);
  if (!status.ok()) return status;
  const Skeleton& skeleton = take.skeleton;
  const MarkerSet& markers = take.markers;
  LeaveOneOutOptions options;
  status = MarkerSolveOptionsFromSettings(config.solver, skeleton, take.mean_pose, &options.frame);
  if (!status.ok()) return status;
  options.clip = config.solver.mode == "clip";
  if (options.clip) {
    status = ClipSolveOptionsFromSettings(config.solver, &options.clip_options);
    if (!status.ok()) return status;
    options.clip_options.ceres.num_threads = 1;  // The markers are the parallel work.
  }
  options.num_threads = config.solver.num_threads;
  options.refine_rounds = config.evaluate.refine_offsets;
  options.refine.prior_frames = config.evaluate.refine_prior_frames;
  options.keep_predictions = config.keep_predictions;
  // A skeleton of unknown unit has no mm: every sample solved.
  options.off_body_tolerance =
      skeleton.unit().known() ? config.evaluate.off_body_mm / (skeleton.unit().metres_per_unit * 1000.0) : 0.0;
  LeaveOneOutReport& loo = result->leave_one_out;
  status = LeaveOneMarkerOut(skeleton, markers, take.observed, options, &loo, [&](int done) {
    if (progress) progress(done, markers.num_markers());
  });
  if (!status.ok()) return Status::Error(take.name + ": " + status.message());
  result->leave_one_out_labels.clear();
  for (int m = 0; m < markers.num_markers(); ++m) result->leave_one_out_labels.push_back(markers.label(m));
  protocol.Add("refine_offsets", config.evaluate.refine_offsets)
      .Add("refine_prior_frames", config.evaluate.refine_prior_frames).Add("off_body_mm", config.evaluate.off_body_mm);

  const bool known = skeleton.unit().known();
  const double mm = known ? skeleton.unit().metres_per_unit * 1000.0 : 1.0;
  const char* unit = known ? "mm" : "skeleton units";
  result->table_csv = "marker,samples,mean,median,p95,max,unit\n";
  auto row = [&](const std::string& label, const PredictionErrorSummary& e) {
    char line[256];
    std::snprintf(line, sizeof(line), "%s,%d,%.6g,%.6g,%.6g,%.6g,%s\n", label.c_str(), e.samples, e.mean * mm,
                  e.median * mm, e.p95 * mm, e.max * mm, unit);
    result->table_csv += line;
    JsonObject o;
    o.Add("marker", label).Add("samples", e.samples).Add("off_body", e.off_body).Add("mean", e.mean * mm)
        .Add("median", e.median * mm).Add("p95", e.p95 * mm).Add("max", e.max * mm);
    return o;
  };
  std::vector<JsonObject> rows;
  for (int m = 0; m < markers.num_markers(); ++m) rows.push_back(row(markers.label(m), loo.markers[m]));
  const JsonObject all = row("all", loo.all);
  result->report.Add("method", "leave_one_out").Add("mode", config.solver.mode).Add("solver", config.solver.solver)
      .Add("protocol", protocol).Add("frames", static_cast<int>(take.observed.size())).Add("unit", unit).Add("seconds", loo.seconds)
      .Add("all", all).Add("per_marker", rows);
  return Status::Ok();
}

Status SmallErrors(const MarkerTake& take, const EvaluateConfig& config, EvaluateResult* result) {
  RepairConfig repair{config.repair, config.solver};
  RepairOptions options;
  Status status = RepairOptionsForTake(take, repair, &options);
  if (!status.ok()) return status;
  SmallErrorRecipe& recipe = result->recipe;
  recipe = DefaultSmallErrorRecipe(take.skeleton.unit().metres_per_unit, config.evaluate.white_noise_mm);
  recipe.seed = static_cast<uint32_t>(config.damage.seed);
  SmallErrorScore& score = result->small_errors;
  status = EvaluateSmallErrors(take.skeleton, take.markers, take.observed, options, recipe, config.evaluate.trials, &score);
  if (!status.ok()) return Status::Error(take.name + ": " + status.message());
  std::vector<JsonObject> seeds;
  for (const SmallErrorSeedScore& s : score.seeds) {
    JsonObject o;
    o.Add("seed", static_cast<int>(s.seed)).Add("damaged", static_cast<double>(s.damaged))
        .Add("flagged", static_cast<double>(s.flagged)).Add("true_positive", static_cast<double>(s.true_positive))
        .Add("own", static_cast<double>(s.own)).Add("own_damaged", static_cast<double>(s.own_damaged));
    seeds.push_back(o);
  }
  result->report.Add("method", "small_errors").Add("frames", static_cast<int>(take.observed.size()))
      .Add("trials", config.evaluate.trials).Add("first_seed", config.damage.seed)
      .Add("white_noise_mm", config.evaluate.white_noise_mm).Add("damaged", static_cast<double>(score.damaged))
      .Add("flagged", static_cast<double>(score.flagged)).Add("true_positive", static_cast<double>(score.true_positive))
      .Add("own", static_cast<double>(score.own)).Add("own_damaged", static_cast<double>(score.own_damaged))
      .Add("recall", score.Recall()).Add("precision", score.Precision())
      .Add("precision_without_own", score.PrecisionWithoutOwn()).Add("seeds", seeds);
  return Status::Ok();
}

// Adds trial row r (weight w of the mean) into the method's mean row m.
void Accumulate(const RepairEvaluationRow& r, double w, RepairEvaluationRow* m) {
  m->method = r.method;
  m->joint_position_error += w * r.joint_position_error;
  m->joint_rotation_error += w * r.joint_rotation_error;
  m->marker_error_mean += w * r.marker_error_mean;
  m->marker_error_rms += w * r.marker_error_rms;
  m->marker_error_max = std::max(m->marker_error_max, r.marker_error_max);
  m->damaged_samples += r.damaged_samples;
  m->covered_samples += r.covered_samples;
  m->velocity_jump += w * r.velocity_jump;
  for (int k = 0; k < kNumDamageKinds; ++k) {
    m->kind_error[k] += w * r.kind_error[k];
    m->kind_samples[k] += r.kind_samples[k];
    m->kind_detected[k] += r.kind_detected[k];
  }
  m->changed_samples += r.changed_samples;
  m->changed_undamaged_samples += r.changed_undamaged_samples;
  m->unlabelled_assigned_samples += r.unlabelled_assigned_samples;
  m->unlabelled_false_samples += r.unlabelled_false_samples;
  m->seconds += w * r.seconds;
}

JsonObject RowJson(const RepairEvaluationRow& r, double cm, double mm) {
  JsonObject o;
  o.Add("method", r.method).Add("joint_position_cm", r.joint_position_error * cm)
      .Add("joint_rotation_deg", r.joint_rotation_error * kDegreesPerRadian)
      .Add("marker_mean_mm", r.marker_error_mean * mm).Add("marker_rms_mm", r.marker_error_rms * mm)
      .Add("marker_max_mm", r.marker_error_max * mm).Add("damaged_samples", r.damaged_samples)
      .Add("covered_samples", r.covered_samples).Add("velocity_jump_mm_per_frame", r.velocity_jump * mm)
      .Add("seconds", r.seconds).Add("precision", r.Precision())
      .Add("unlabelled_assigned_samples", r.unlabelled_assigned_samples)
      .Add("unlabelled_false_samples", r.unlabelled_false_samples);
  for (int k = 0; k < kNumDamageKinds; ++k) {
    const std::string kind = kDamageKindNames[k];
    o.Add(kind + "_mean_mm", r.kind_error[k] * mm).Add(kind + "_samples", r.kind_samples[k])
        .Add(kind + "_recall", r.Recall(k));
  }
  return o;
}

Status RepairTable(const MarkerTake& take, const EvaluateConfig& config,
                   const std::function<void(int, int)>& progress, EvaluateResult* result) {
  RepairConfig repair{config.repair, config.solver};
  RepairOptions options;
  Status status = RepairOptionsForTake(take, repair, &options);
  if (!status.ok()) return status;
  CorruptionOptions damage;
  status = CorruptionOptionsFromSettings(config.damage, take.skeleton.unit(), &damage);
  if (!status.ok()) return status;
  const double cm = take.skeleton.unit().metres_per_unit * 100.0, mm = cm * 10.0;
  result->table_csv = "trial,seed,method,joint_position_cm,joint_rotation_deg,marker_mean_mm,marker_rms_mm,"
                      "marker_max_mm,damaged_samples,covered_samples,velocity_jump_mm_per_frame,seconds\n";
  std::vector<JsonObject> per_trial;
  for (int trial = 0; trial < config.evaluate.trials; ++trial) {
    damage.seed = static_cast<uint32_t>(config.damage.seed + trial);
    std::vector<RepairEvaluationRow> rows;
    status = EvaluateRepairTrial(take.skeleton, take.markers, take.observed, damage, options, &rows);
    if (!status.ok()) return Status::Error(take.name + ": " + status.message());
    std::vector<RepairEvaluationRow>& means = result->mean_rows;
    if (means.empty()) means.assign(rows.size(), RepairEvaluationRow());
    for (size_t i = 0; i < rows.size(); ++i) {
      const RepairEvaluationRow& r = rows[i];
      Accumulate(r, 1.0 / config.evaluate.trials, &means[i]);
      char line[512];
      std::snprintf(line, sizeof(line), "%d,%u,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%.6g,%.4g\n", trial, damage.seed,
                    r.method.c_str(), r.joint_position_error * cm, r.joint_rotation_error * kDegreesPerRadian,
                    r.marker_error_mean * mm, r.marker_error_rms * mm, r.marker_error_max * mm, r.damaged_samples,
                    r.covered_samples, r.velocity_jump * mm, r.seconds);
      result->table_csv += line;
      JsonObject o;
      o.Add("trial", trial).Add("seed", static_cast<double>(damage.seed)).Merge(RowJson(r, cm, mm));
      per_trial.push_back(o);
      result->trial_rows.push_back(r);
      result->trial_of_row.push_back(trial);
      result->seed_of_row.push_back(damage.seed);
    }
    if (progress) progress(trial + 1, config.evaluate.trials);
  }
  std::vector<JsonObject> methods;
  const RepairEvaluationRow* ours = nullptr;
  for (const RepairEvaluationRow& r : result->mean_rows) {
    methods.push_back(RowJson(r, cm, mm));
    if (r.method == "ours") ours = &r;
  }
  JsonObject ratios;
  if (ours != nullptr && ours->joint_position_error > 0.0) {
    for (const RepairEvaluationRow& r : result->mean_rows) {
      if (r.method == "clean" || r.method == "ours") continue;
      ratios.Add(r.method, r.joint_position_error / ours->joint_position_error);
    }
  }
  result->report.Add("method", "repair").Add("frames", static_cast<int>(take.observed.size()))
      .Add("trials", config.evaluate.trials).Add("first_seed", config.damage.seed)
      .Add("reference", config.repair.reference).Add("methods", methods)
      .Add("position_error_ratio_to_ours", ratios).Add("per_trial", per_trial);
  return Status::Ok();
}

}  // namespace

Status RunEvaluate(const MarkerTake& take, const EvaluateConfig& config,
                   const std::function<void(int done, int total)>& progress, EvaluateResult* result) {
  *result = EvaluateResult();
  Status status = EvaluateSettingOptions().Validate(config.evaluate);
  if (status.ok()) status = EvaluateMethodOption().Validate(MethodSetting{config.method});
  if (!status.ok()) return status;
  if (config.method == "retarget") {
    return Status::Error("--method=retarget: a source and characters, not a marker take (RunEvaluateRetarget)");
  }
  if (config.method == "leave_one_out") return LeaveOneOut(take, config, progress, result);
  if (config.method == "small_errors") return SmallErrors(take, config, result);
  return RepairTable(take, config, progress, result);
}

}  // namespace mocapsolve
