// mocapsolve evaluate: marker repair against the usual gap fills on the same damage, the
// analogue of the thesis' Table 1 (problems/marker_repair/repair_evaluation.h).
#include <cmath>
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "kinematics/quote_token.h"
#include "apps/corruption_flags.h"
#include "apps/progress.h"
#include "apps/repair_flags.h"
#include "apps/solver_flags.h"
#include "io/atomic_file.h"
#include "io/marker_set_file.h"
#include "problems/marker_repair/repair_evaluation.h"
#include "problems/marker_repair/small_error_evaluation.h"
#include "problems/marker_solve/leave_one_out.h"

DEFINE_int32(trials, 1, "Damage draws to average over (seeds --corrupt_seed, +1, ...).");
DEFINE_string(table_csv, "", "Also write the table as CSV (repair: one row per method and trial; leave_one_out: one "
              "row per marker).");
DEFINE_double(white_noise_mm, 0.0, "--method=small_errors: white noise (mm per axis) added to every sample before "
              "the damage, and to the undamaged take the own detections come from (a noise-free synthetic take: 1).");
DECLARE_string(method);  // apps/blend_command.cc; here repair | leave_one_out | small_errors.
DECLARE_int32(num_threads);

namespace mocapsolve {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

// --method=leave_one_out: every marker predicted by the solve of the others
// (problems/marker_solve/leave_one_out.h); no damage, no ground truth needed.
Status RunLeaveOneOut(const MarkerTake& take) {
  const Skeleton& skeleton = take.skeleton;
  const MarkerSet& markers = take.markers;
  LeaveOneOutOptions options;
  Status status = MarkerSolveOptionsFromFlags(skeleton.unit(), &options.frame);
  if (!status.ok()) return status;
  options.frame.rest_rotations = take.mean_pose;
  const SolverSettings solver = SolverSettingsFromFlags();
  options.clip = solver.mode == "clip";
  if (options.clip) {
    status = ClipSolveOptionsFromFlags(&options.clip_options);
    if (!status.ok()) return status;
    options.clip_options.ceres.num_threads = 1;  // The markers are the parallel work.
  }
  options.num_threads = solver.num_threads;
  LeaveOneOutReport result;
  Progress progress("leave one out (" + solver.solver + ", " + solver.mode + ")", markers.num_markers(), FLAGS_quiet,
                    "markers");
  status = LeaveOneMarkerOut(skeleton, markers, take.observed, options, &result,
                             [&](int done) { progress.Update(done); });
  if (!status.ok()) return Status::Error(FLAGS_markers + ": " + status.message());

  const bool known = skeleton.unit().known();
  const double mm = known ? skeleton.unit().metres_per_unit * 1000.0 : 1.0;
  const char* unit = known ? "mm" : "skeleton units";
  std::printf("%d frames, %d markers; each marker predicted by the %s solve of the others (%s), in %s\n",
              static_cast<int>(take.observed.size()), markers.num_markers(), solver.mode.c_str(), solver.solver.c_str(),
              unit);
  std::printf("| marker | samples | mean | median | 95th pct | max |\n|---|---|---|---|---|---|\n");
  std::string csv = "marker,samples,mean,median,p95,max,unit\n";
  std::vector<JsonObject> rows;
  auto row = [&](const std::string& label, const PredictionErrorSummary& e) {
    std::printf("| %s | %d | %.2f | %.2f | %.2f | %.2f |\n", TerminalText(label).c_str(), e.samples, e.mean * mm, e.median * mm,
                e.p95 * mm, e.max * mm);
    char line[256];
    std::snprintf(line, sizeof(line), "%s,%d,%.6g,%.6g,%.6g,%.6g,%s\n", label.c_str(), e.samples, e.mean * mm,
                  e.median * mm, e.p95 * mm, e.max * mm, unit);
    csv += line;
    JsonObject o;
    o.Add("marker", label).Add("samples", e.samples).Add("mean", e.mean * mm).Add("median", e.median * mm)
        .Add("p95", e.p95 * mm).Add("max", e.max * mm);
    return o;
  };
  for (int m = 0; m < markers.num_markers(); ++m) rows.push_back(row(markers.label(m), result.markers[m]));
  JsonObject all = row("all", result.all);
  std::printf("prediction error over every sample: median %.2f %s, mean %.2f, 95th percentile %.2f (%.1f s)\n",
              result.all.median * mm, unit, result.all.mean * mm, result.all.p95 * mm, result.seconds);
  if (!FLAGS_table_csv.empty()) {
    status = WriteFileAtomically(FLAGS_table_csv, csv);
    if (!status.ok()) return status;
  }
  JsonObject report;
  report.Add("markers", FLAGS_markers).Add("method", "leave_one_out").Add("mode", solver.mode)
      .Add("solver", solver.solver).Add("frames", static_cast<int>(take.observed.size())).Add("unit", unit)
      .Add("seconds", result.seconds).Add("all", all).Add("per_marker", rows);
  return WriteReport(report);
}

// --method=small_errors: the recipe of 1-4 cm jumps and jitter (small_error_evaluation.h)
// over --trials seeds from --corrupt_seed; recall, precision raw and without the samples
// the repair also flags on the undamaged take (listed: the take's own glitches).
Status RunSmallErrors(const MarkerTake& take) {
  const Skeleton& skeleton = take.skeleton;
  RepairOptions options;
  Status status = RepairOptionsFromFlags(skeleton, &options);
  if (!status.ok()) return status;
  SetRepairRestRotations(take.mean_pose, &options);  // As --method=repair and `mocapsolve repair`.
  if (!(FLAGS_white_noise_mm >= 0.0)) return Status::Error("--white_noise_mm: expected >= 0");
  SmallErrorRecipe recipe = DefaultSmallErrorRecipe(skeleton.unit().metres_per_unit, FLAGS_white_noise_mm);
  recipe.seed = static_cast<uint32_t>(CorruptionSettingsFromFlags().corrupt_seed);
  SmallErrorScore score;
  status = EvaluateSmallErrors(skeleton, take.markers, take.observed, options, recipe, FLAGS_trials, &score);
  if (!status.ok()) return Status::Error(FLAGS_markers + ": " + status.message());
  const int nf = static_cast<int>(take.observed.size()), nm = take.markers.num_markers();
  std::printf("%d frames, %d markers; per seed %d jumps of 1-4 cm (1-%d frames) and %d runs of 2 cm jitter, white "
              "noise %.2f mm\n", nf, nm, recipe.jumps, recipe.jump_max_frames, recipe.jitter_runs, FLAGS_white_noise_mm);
  std::printf("| seed | damaged | flagged | found | recall | precision | own flagged (damaged) | precision without own "
              "|\n|---|---|---|---|---|---|---|---|\n");
  std::vector<JsonObject> seeds;
  for (const SmallErrorSeedScore& s : score.seeds) {
    std::printf("| %u | %ld | %ld | %ld | %.3f | %.3f | %ld (%ld) | %.3f |\n", s.seed, s.damaged, s.flagged,
                s.true_positive, s.Recall(), s.Precision(), s.own, s.own_damaged, s.PrecisionWithoutOwn());
    JsonObject o;
    o.Add("seed", static_cast<int>(s.seed)).Add("damaged", static_cast<double>(s.damaged))
        .Add("flagged", static_cast<double>(s.flagged)).Add("true_positive", static_cast<double>(s.true_positive))
        .Add("own", static_cast<double>(s.own)).Add("own_damaged", static_cast<double>(s.own_damaged));
    seeds.push_back(o);
  }
  std::printf("all seeds: recall %.3f, precision %.3f, precision without the take's own detections %.3f (%ld flagged "
              "samples excluded, %ld of them damaged)\n", score.Recall(), score.Precision(),
              score.PrecisionWithoutOwn(), score.own, score.own_damaged);
  // The undamaged take's own detections (first seed), as runs per marker, and the damage missed.
  auto runs = [&](const SampleFlags& flags, const SampleFlags* unless) {
    std::string text;
    for (int m = 0; m < nm; ++m) {
      for (int f = 0; f < nf; ++f) {
        if (!flags[f][m] || (unless != nullptr && (*unless)[f][m])) continue;
        int last = f;
        while (last + 1 < nf && flags[last + 1][m] && (unless == nullptr || !(*unless)[last + 1][m])) ++last;
        text += " " + take.markers.label(m) + " " + std::to_string(f) + (last > f ? "-" + std::to_string(last) : "");
        f = last;
      }
    }
    return text;
  };
  if (!score.seeds.empty()) {
    std::printf("flagged on the undamaged take (seed %u):%s\n", score.seeds[0].seed,
                runs(score.seeds[0].own_samples, nullptr).c_str());
  }
  for (const SmallErrorSeedScore& s : score.seeds) {
    std::printf("damaged samples missed (seed %u):%s\n", s.seed, runs(s.damaged_samples, &s.flagged_samples).c_str());
  }
  JsonObject report;
  report.Add("markers", FLAGS_markers).Add("method", "small_errors").Add("frames", nf).Add("trials", FLAGS_trials)
      .Add("first_seed", CorruptionSettingsFromFlags().corrupt_seed).Add("white_noise_mm", FLAGS_white_noise_mm)
      .Add("damaged", static_cast<double>(score.damaged)).Add("flagged", static_cast<double>(score.flagged))
      .Add("true_positive", static_cast<double>(score.true_positive)).Add("own", static_cast<double>(score.own))
      .Add("own_damaged", static_cast<double>(score.own_damaged)).Add("recall", score.Recall())
      .Add("precision", score.Precision()).Add("precision_without_own", score.PrecisionWithoutOwn())
      .Add("seeds", seeds);
  return WriteReport(report);
}

Status RunEvaluate(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  std::vector<std::string> inputs;
  Status checked = MarkerTakeInputs(&inputs);
  if (!checked.ok()) return checked;
  if (FLAGS_method != "repair" && FLAGS_method != "leave_one_out" && FLAGS_method != "small_errors") {
    return Status::Error("--method: expected repair, leave_one_out or small_errors, got '" + FLAGS_method + "'");
  }
  if (FLAGS_trials < 1 || FLAGS_trials > 1000) return Status::Error("--trials: expected 1..1000");
  if (!FLAGS_table_csv.empty()) {
    for (const std::string& in : inputs) {
      Status status = CheckNotAnInput(FLAGS_table_csv, in);
      if (!status.ok()) return status;
    }
  }
  MarkerTake take;
  Status status = LoadMarkerTake(&take);
  if (!status.ok()) return status;
  if (FLAGS_method == "leave_one_out") return RunLeaveOneOut(take);
  if (FLAGS_method == "small_errors") return RunSmallErrors(take);
  const Skeleton& skeleton = take.skeleton;
  const MarkerSet& markers = take.markers;
  const MarkerObservations& clean = take.observed;
  RepairOptions options;
  status = RepairOptionsFromFlags(skeleton, &options);
  if (!status.ok()) return status;
  SetRepairRestRotations(take.mean_pose, &options);
  CorruptionOptions damage;
  status = CorruptionOptionsFromFlags(skeleton.unit(), &damage);
  if (!status.ok()) return status;

  const double cm = skeleton.unit().metres_per_unit * 100.0, mm = cm * 10.0;
  std::vector<RepairEvaluationRow> mean_rows;
  std::string csv = "trial,seed,method,joint_position_cm,joint_rotation_deg,marker_mean_mm,marker_rms_mm,"
                    "marker_max_mm,damaged_samples,covered_samples,velocity_jump_mm_per_frame,seconds\n";
  Progress trials_progress("evaluate", FLAGS_trials, FLAGS_quiet, "trials");
  for (int trial = 0; trial < FLAGS_trials; ++trial) {
    damage.seed = static_cast<uint32_t>(CorruptionSettingsFromFlags().corrupt_seed + trial);
    std::vector<RepairEvaluationRow> rows;
    status = EvaluateRepairTrial(skeleton, markers, clean, damage, options, &rows);
    if (!status.ok()) return Status::Error(FLAGS_markers + ": " + status.message());
    if (mean_rows.empty()) mean_rows.assign(rows.size(), RepairEvaluationRow());
    for (size_t i = 0; i < rows.size(); ++i) {
      const RepairEvaluationRow& r = rows[i];
      RepairEvaluationRow& m = mean_rows[i];
      const double w = 1.0 / FLAGS_trials;
      m.method = r.method;
      m.joint_position_error += w * r.joint_position_error;
      m.joint_rotation_error += w * r.joint_rotation_error;
      m.marker_error_mean += w * r.marker_error_mean;
      m.marker_error_rms += w * r.marker_error_rms;
      m.marker_error_max = std::max(m.marker_error_max, r.marker_error_max);
      m.damaged_samples += r.damaged_samples;
      m.covered_samples += r.covered_samples;
      m.velocity_jump += w * r.velocity_jump;
      for (int k = 0; k < kNumDamageKinds; ++k) {
        m.kind_error[k] += w * r.kind_error[k];
        m.kind_samples[k] += r.kind_samples[k];
        m.kind_detected[k] += r.kind_detected[k];
      }
      m.changed_samples += r.changed_samples;
      m.changed_undamaged_samples += r.changed_undamaged_samples;
      m.unlabelled_assigned_samples += r.unlabelled_assigned_samples;
      m.unlabelled_false_samples += r.unlabelled_false_samples;
      m.seconds += w * r.seconds;
      char line[512];
      std::snprintf(line, sizeof(line), "%d,%u,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%.6g,%.4g\n", trial, damage.seed,
                    r.method.c_str(), r.joint_position_error * cm, r.joint_rotation_error * kDegreesPerRadian,
                    r.marker_error_mean * mm, r.marker_error_rms * mm, r.marker_error_max * mm, r.damaged_samples,
                    r.covered_samples, r.velocity_jump * mm, r.seconds);
      csv += line;
    }
    trials_progress.Update(trial + 1);
  }

  std::printf("%d frames, %d markers, %d trial(s); errors against the solve of the clean markers\n",
              static_cast<int>(clean.size()), markers.num_markers(), FLAGS_trials);
  std::printf("| method | joint pos (cm) | joint rot (deg) | damaged markers mean / RMS / max (mm) | covered "
              "| velocity jump (mm/frame) | time (s) |\n|---|---|---|---|---|---|---|\n");
  std::vector<JsonObject> json_rows;
  for (const RepairEvaluationRow& r : mean_rows) {
    std::printf("| %s | %.3f | %.3f | %.2f / %.2f / %.1f | %.1f %% | %.3f | %.3f |\n", r.method.c_str(),
                r.joint_position_error * cm, r.joint_rotation_error * kDegreesPerRadian, r.marker_error_mean * mm,
                r.marker_error_rms * mm, r.marker_error_max * mm,
                r.damaged_samples > 0 ? 100.0 * r.covered_samples / r.damaged_samples : 100.0,
                r.velocity_jump * mm, r.seconds);
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
    json_rows.push_back(o);
  }
  // Per damage kind present: each method's mean error on it, and the share it detected
  // (changed; for gaps, filled), then the precision of all it changed.
  std::string kinds;
  for (int k = 0; k < kNumDamageKinds; ++k) {
    if (mean_rows.empty() || mean_rows.back().kind_samples[k] == 0) continue;
    kinds += std::string(kinds.empty() ? "" : " | ") + kDamageKindNames[k];
  }
  std::printf("damaged-marker mean error (mm) and recall by kind: %s; precision of all changed samples\n",
              kinds.c_str());
  for (const RepairEvaluationRow& r : mean_rows) {
    if (r.method == "clean") continue;
    std::printf("  %-15s", r.method.c_str());
    for (int k = 0; k < kNumDamageKinds; ++k) {
      if (r.kind_samples[k] == 0) continue;
      std::printf(" %7.2f %5.1f%%", r.kind_error[k] * mm, 100.0 * r.Recall(k));
    }
    std::printf("   precision %.1f%% (%d changed)\n", 100.0 * r.Precision(), r.changed_samples);
  }
  const int unlabelled = DamageKindIndex('u');
  if (!mean_rows.empty() && mean_rows.back().kind_samples[unlabelled] > 0) {
    const RepairEvaluationRow& r = mean_rows.back();
    std::printf("unlabelled samples (ours): %d of %d assigned to their own marker (%.1f%%), %d to another; %d "
                "(%.1f%%) kept in the output bit for bit (the rest cut by later stages, as trimming beside gaps)\n",
                r.unlabelled_assigned_samples, r.kind_samples[unlabelled],
                100.0 * r.unlabelled_assigned_samples / r.kind_samples[unlabelled], r.unlabelled_false_samples,
                r.kind_detected[unlabelled], 100.0 * r.Recall(unlabelled));
  }
  auto find = [&](const char* name) -> const RepairEvaluationRow* {
    for (const RepairEvaluationRow& r : mean_rows) {
      if (r.method == name) return &r;
    }
    return nullptr;
  };
  const RepairEvaluationRow* ours = find("ours");
  JsonObject ratios;
  if (ours != nullptr && ours->joint_position_error > 0.0) {
    std::printf("joint position error of each method / ours:");
    for (const RepairEvaluationRow& r : mean_rows) {
      if (r.method == "clean" || r.method == "ours") continue;
      const double ratio = r.joint_position_error / ours->joint_position_error;
      std::printf(" %s %.1fx", r.method.c_str(), ratio);
      ratios.Add(r.method, ratio);
    }
    std::printf("\n");
  }
  if (!FLAGS_table_csv.empty()) {
    status = WriteFileAtomically(FLAGS_table_csv, csv);
    if (!status.ok()) return status;
  }
  JsonObject report;
  report.Add("markers", FLAGS_markers).Add("method", "repair").Add("frames", static_cast<int>(clean.size()))
      .Add("trials", FLAGS_trials)
      .Add("first_seed", CorruptionSettingsFromFlags().corrupt_seed).Add("reference", RepairSettingsFromFlags().reference).Add("methods", json_rows)
      .Add("position_error_ratio_to_ours", ratios);
  return WriteReport(report);
}

const std::string kEvaluateFlags = std::string("subject,skeleton,skeleton_units,markers,markerset,axes,marker_scale,"
                                               "report,quiet,method,white_noise_mm");

}  // namespace

extern const Command kEvaluateCommand = {
    "evaluate", "score marker repair against linear, polynomial, PCA and reference-only fills",
    "mocapsolve evaluate (--skeleton=S --markerset=J.json | --subject=S.json) --markers=CLEAN.c3d|.trc [--trials=N] "
    "[--corrupt_seed=1 --gaps=10 ...] [--table_csv=t.csv] [--report=r.json]\n"
    "       mocapsolve evaluate --method=leave_one_out (--subject=S.json | ...) --markers=TAKE.c3d|.trc "
    "[--mode=frame|clip] [--table_csv=t.csv]\n"
    "       mocapsolve evaluate --method=small_errors (--subject=S.json | ...) --markers=TAKE.c3d|.trc [--trials=5] "
    "[--white_noise_mm=1]\n\n"
    "Damages the clean markers (as `corrupt` does, in the skeleton's frame), runs every method\n"
    "on the same damage and prints the analogue of the thesis' Table 1: mean global joint\n"
    "position (cm) and rotation (deg) error of the per-frame solve after each method against\n"
    "the solve of the clean markers, the marker error over the damaged samples, and the\n"
    "velocity jump at the edges of damaged runs (the 'clean' row: the natural one).\n"
    "Clean markers from a BVH: mocapsolve markers --motion=X.bvh --markerset=auto:3\n"
    "--out=clean.c3d --write_markerset=set.json, then evaluate with --skeleton=X.bvh.\n"
    "--method=leave_one_out measures a real take without ground truth: for each marker, the take\n"
    "is solved without it (per frame, and with --mode=clip also as a whole clip) and the marker\n"
    "is predicted from the solution; prints the prediction error per marker and over all samples\n"
    "(mean, median, 95th percentile, max).\n"
    "--method=small_errors adds 12 jumps of 1-4 cm and 3 runs of 2 cm jitter per seed to the take\n"
    "(after --white_noise_mm of noise) and prints the repair's recall and precision on them, the\n"
    "latter also without the samples it flags on the undamaged take (the take's own glitches).",
    __FILE__, RunEvaluate, kEvaluateFlags.c_str(),
    {RepairSolverOptions()
         .WithDefault("num_threads", "2",
                      "Threads: leave_one_out solves this many markers at once; repair runs its solves on two "
                      "threads when >= 2. Speed only: the results do not depend on it.")
         .options(),
     SolverOptions().Only("mode").options(),  // leave_one_out's frame or clip solve.
     RepairSettingOptions().options(), CorruptionSettingOptions().options()},
    {{"method", "repair",
      "repair: damage the markers and score repair against the usual fills (Table 1); leave_one_out: "
      "predict each marker from the solve of the others, on the take as it is; small_errors: recall and precision "
      "of the repair's detections on 1-4 cm jumps and jitter."},
    }};

}  // namespace mocapsolve
