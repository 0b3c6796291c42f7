// mocapsolve evaluate: marker repair against the usual gap fills on the same damage, the
// analogue of the thesis' Table 1 (problems/marker_repair/repair_evaluation.h).
#include <cstdio>
#include <memory>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "kinematics/quote_token.h"
#include "apps/corruption_flags.h"
#include "apps/progress.h"
#include "apps/repair_flags.h"
#include "apps/solver_flags.h"
#include "io/atomic_file.h"
#include "tasks/evaluate_task.h"

DEFINE_string(table_csv, "", "Also write the table as CSV (repair: one row per method and trial; leave_one_out: one "
              "row per marker).");
DECLARE_string(method);  // apps/blend_command.cc; here repair | leave_one_out | small_errors.

namespace mocapsolve {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

// --method=leave_one_out's console table: each marker's prediction error.
void PrintLeaveOneOut(const MarkerTake& take, const EvaluateConfig& config, const LeaveOneOutReport& result) {
  const bool known = take.skeleton.unit().known();
  const double mm = known ? take.skeleton.unit().metres_per_unit * 1000.0 : 1.0;
  const char* unit = known ? "mm" : "skeleton units";
  std::printf("%d frames, %d markers; each marker predicted by the %s solve of the others (%s), in %s\n",
              static_cast<int>(take.observed.size()), take.markers.num_markers(), config.solver.mode.c_str(),
              config.solver.solver.c_str(), unit);
  std::printf("| marker | samples | mean | median | 95th pct | max |\n|---|---|---|---|---|---|\n");
  auto row = [&](const std::string& label, const PredictionErrorSummary& e) {
    std::printf("| %s | %d | %.2f | %.2f | %.2f | %.2f |\n", TerminalText(label).c_str(), e.samples, e.mean * mm,
                e.median * mm, e.p95 * mm, e.max * mm);
  };
  for (int m = 0; m < take.markers.num_markers(); ++m) row(take.markers.label(m), result.markers[m]);
  row("all", result.all);
  std::printf("prediction error over every sample: median %.2f %s, mean %.2f, 95th percentile %.2f (%.1f s)\n",
              result.all.median * mm, unit, result.all.mean * mm, result.all.p95 * mm, result.seconds);
}

// --method=small_errors' console table: recall and precision per seed, the undamaged
// take's own detections and the damage missed, as runs per marker.
void PrintSmallErrors(const MarkerTake& take, const EvaluateConfig& config, const EvaluateResult& result) {
  const SmallErrorRecipe& recipe = result.recipe;
  const SmallErrorScore& score = result.small_errors;
  const int nf = static_cast<int>(take.observed.size()), nm = take.markers.num_markers();
  std::printf("%d frames, %d markers; per seed %d jumps of 1-4 cm (1-%d frames) and %d runs of 2 cm jitter, white "
              "noise %.2f mm\n", nf, nm, recipe.jumps, recipe.jump_max_frames, recipe.jitter_runs,
              config.evaluate.white_noise_mm);
  std::printf("| seed | damaged | flagged | found | recall | precision | own flagged (damaged) | precision without own "
              "|\n|---|---|---|---|---|---|---|---|\n");
  for (const SmallErrorSeedScore& s : score.seeds) {
    std::printf("| %u | %ld | %ld | %ld | %.3f | %.3f | %ld (%ld) | %.3f |\n", s.seed, s.damaged, s.flagged,
                s.true_positive, s.Recall(), s.Precision(), s.own, s.own_damaged, s.PrecisionWithoutOwn());
  }
  std::printf("all seeds: recall %.3f, precision %.3f, precision without the take's own detections %.3f (%ld flagged "
              "samples excluded, %ld of them damaged)\n", score.Recall(), score.Precision(),
              score.PrecisionWithoutOwn(), score.own, score.own_damaged);
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
}

// --method=repair's console table (the thesis' Table 1): each method's mean over the trials.
void PrintRepairTable(const MarkerTake& take, const EvaluateConfig& config, const EvaluateResult& result) {
  const std::vector<RepairEvaluationRow>& mean_rows = result.mean_rows;
  const double cm = take.skeleton.unit().metres_per_unit * 100.0, mm = cm * 10.0;
  std::printf("%d frames, %d markers, %d trial(s); errors against the solve of the clean markers\n",
              static_cast<int>(take.observed.size()), take.markers.num_markers(), config.evaluate.trials);
  std::printf("| method | joint pos (cm) | joint rot (deg) | damaged markers mean / RMS / max (mm) | covered "
              "| velocity jump (mm/frame) | time (s) |\n|---|---|---|---|---|---|---|\n");
  for (const RepairEvaluationRow& r : mean_rows) {
    std::printf("| %s | %.3f | %.3f | %.2f / %.2f / %.1f | %.1f %% | %.3f | %.3f |\n", r.method.c_str(),
                r.joint_position_error * cm, r.joint_rotation_error * kDegreesPerRadian, r.marker_error_mean * mm,
                r.marker_error_rms * mm, r.marker_error_max * mm,
                r.damaged_samples > 0 ? 100.0 * r.covered_samples / r.damaged_samples : 100.0,
                r.velocity_jump * mm, r.seconds);
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
  const RepairEvaluationRow* ours = nullptr;
  for (const RepairEvaluationRow& r : mean_rows) {
    if (r.method == "ours") ours = &r;
  }
  if (ours != nullptr && ours->joint_position_error > 0.0) {
    std::printf("joint position error of each method / ours:");
    for (const RepairEvaluationRow& r : mean_rows) {
      if (r.method == "clean" || r.method == "ours") continue;
      std::printf(" %s %.1fx", r.method.c_str(), r.joint_position_error / ours->joint_position_error);
    }
    std::printf("\n");
  }
}

Status EvaluateMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  std::vector<std::string> inputs;
  Status checked = MarkerTakeInputs(&inputs);
  if (!checked.ok()) return checked;
  EvaluateConfig config;
  config.method = FLAGS_method;
  ReadOptionFlags(EvaluateSettingOptions(), &config.evaluate);
  config.repair = RepairSettingsFromFlags();
  config.solver = SolverSettingsFromFlags();
  config.damage = CorruptionSettingsFromFlags();
  if (config.method != "repair" && config.method != "leave_one_out" && config.method != "small_errors") {
    return Status::Error("--method: expected repair, leave_one_out or small_errors, got '" + config.method + "'");
  }
  if (!FLAGS_table_csv.empty()) {
    for (const std::string& in : inputs) {
      Status status = CheckNotAnInput(FLAGS_table_csv, in);
      if (!status.ok()) return status;
    }
  }
  MarkerTake take;
  Status status = LoadMarkerTake(&take);
  if (!status.ok()) return status;
  std::unique_ptr<Progress> progress;
  if (config.method == "leave_one_out") {
    progress = std::make_unique<Progress>("leave one out (" + config.solver.solver + ", " + config.solver.mode + ")",
                                          take.markers.num_markers(), FLAGS_quiet, "markers");
  } else if (config.method == "repair") {
    progress = std::make_unique<Progress>("evaluate", config.evaluate.trials, FLAGS_quiet, "trials");
  }
  EvaluateResult result;
  status = RunEvaluate(take, config, [&](int done, int) { if (progress) progress->Update(done); }, &result);
  if (!status.ok()) return status;
  if (config.method == "leave_one_out") PrintLeaveOneOut(take, config, result.leave_one_out);
  if (config.method == "small_errors") PrintSmallErrors(take, config, result);
  if (config.method == "repair") PrintRepairTable(take, config, result);
  if (!FLAGS_table_csv.empty() && !result.table_csv.empty()) {
    status = WriteFileAtomically(FLAGS_table_csv, result.table_csv);
    if (!status.ok()) return status;
  }
  JsonObject report;
  report.Add("markers", FLAGS_markers).Merge(result.report);
  return WriteReport(report);
}

const std::string kEvaluateFlags = std::string("subject,skeleton,skeleton_units,markers,markerset,axes,marker_scale,"
                                               "report,quiet,method");

}  // namespace

extern const Command kEvaluateCommand = {
    "evaluate", "score marker repair against linear, polynomial, PCA and reference-only fills",
    "mocapsolve evaluate (--skeleton=S --markerset=J.json | --subject=S.json) --markers=CLEAN.c3d|.trc [--trials=N] "
    "[--seed=1 --gaps=10 ...] [--table_csv=t.csv] [--report=r.json]\n"
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
    __FILE__, EvaluateMain, kEvaluateFlags.c_str(),
    {EvaluateSolverOptions().options(),
     SolverOptions().Only("mode").options(),  // leave_one_out's frame or clip solve.
     RepairSettingOptions().options(), CorruptionSettingOptions().options(), EvaluateSettingOptions().options()},
    {{"method", "repair",
      "repair: damage the markers and score repair against the usual fills (Table 1); leave_one_out: "
      "predict each marker from the solve of the others, on the take as it is; small_errors: recall and precision "
      "of the repair's detections on 1-4 cm jumps and jitter."},
    }};

}  // namespace mocapsolve
