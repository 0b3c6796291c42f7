#include "tasks/evaluate_summary.h"

#include <string>

#include "kinematics/quote_token.h"
#include "tasks/console_text.h"

namespace mocapsolve {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

// --method=leave_one_out's console table: each marker's prediction error.
std::string LeaveOneOutTable(const MarkerTake& take, const EvaluateConfig& config, const EvaluateResult& evaluated) {
  const LeaveOneOutReport& result = evaluated.leave_one_out;
  const std::vector<std::string>& labels = evaluated.leave_one_out_labels;
  std::string text;
  const bool known = take.skeleton.unit().known();
  const double mm = known ? take.skeleton.unit().metres_per_unit * 1000.0 : 1.0;
  const char* unit = known ? "mm" : "skeleton units";
  const bool split = config.evaluate.protocol == "time_split";
  const int frames = take.trajectories.num_frames();
  AppendF(&text, "%s: %d frames%s, %d markers; each marker predicted by the %s solve of the others (%s)%s, in %s\n",
          config.evaluate.protocol.c_str(), split ? frames - frames / 2 : frames,
          split ? " (the second half; the subject fitted on the first)" : "", static_cast<int>(labels.size()),
          config.solver.mode.c_str(), config.solver.solver.c_str(),
          config.evaluate.refine_offsets > 0 ? ", the others' offsets refined on the take" : "", unit);
  AppendF(&text, "| marker | samples | mean | median | 95th pct | max |\n|---|---|---|---|---|---|\n");
  auto row = [&](const std::string& label, const PredictionErrorSummary& e) {
    AppendF(&text, "| %s | %d | %.2f | %.2f | %.2f | %.2f |\n", TerminalText(label).c_str(), e.samples, e.mean * mm,
            e.median * mm, e.p95 * mm, e.max * mm);
  };
  for (size_t m = 0; m < labels.size(); ++m) row(labels[m], result.markers[m]);
  row("all", result.all);
  AppendF(&text, "prediction error over every sample: median %.2f %s, mean %.2f, 95th percentile %.2f (%.1f s)\n",
          result.all.median * mm, unit, result.all.mean * mm, result.all.p95 * mm, result.seconds);
  return text;
}

// --method=small_errors' console table: recall and precision per seed, the undamaged
// take's own detections and the damage missed, as runs per marker.
std::string SmallErrorsTable(const MarkerTake& take, const EvaluateConfig& config, const EvaluateResult& result) {
  std::string text;
  const SmallErrorRecipe& recipe = result.recipe;
  const SmallErrorScore& score = result.small_errors;
  const int nf = static_cast<int>(take.observed.size()), nm = take.markers.num_markers();
  AppendF(&text,
          "%d frames, %d markers; per seed %d jumps of 1-4 cm (1-%d frames) and %d runs of 2 cm jitter, white "
          "noise %.2f mm\n",
          nf, nm, recipe.jumps, recipe.jump_max_frames, recipe.jitter_runs, config.evaluate.white_noise_mm);
  AppendF(&text,
          "| seed | damaged | flagged | found | recall | precision | own flagged (damaged) | precision without own "
          "|\n|---|---|---|---|---|---|---|---|\n");
  for (const SmallErrorSeedScore& s : score.seeds) {
    AppendF(&text, "| %u | %ld | %ld | %ld | %.3f | %.3f | %ld (%ld) | %.3f |\n", s.seed, s.damaged, s.flagged,
            s.true_positive, s.Recall(), s.Precision(), s.own, s.own_damaged, s.PrecisionWithoutOwn());
  }
  AppendF(&text,
          "all seeds: recall %.3f, precision %.3f, precision without the take's own detections %.3f (%ld flagged "
          "samples excluded, %ld of them damaged)\n",
          score.Recall(), score.Precision(), score.PrecisionWithoutOwn(), score.own, score.own_damaged);
  auto runs = [&](const SampleFlags& flags, const SampleFlags* unless) {
    std::string list;
    for (int m = 0; m < nm; ++m) {
      for (int f = 0; f < nf; ++f) {
        if (!flags[f][m] || (unless != nullptr && (*unless)[f][m])) continue;
        int last = f;
        while (last + 1 < nf && flags[last + 1][m] && (unless == nullptr || !(*unless)[last + 1][m])) ++last;
        list += " " + take.markers.label(m) + " " + std::to_string(f) + (last > f ? "-" + std::to_string(last) : "");
        f = last;
      }
    }
    return list;
  };
  if (!score.seeds.empty()) {
    AppendF(&text, "flagged on the undamaged take (seed %u):%s\n", score.seeds[0].seed,
            runs(score.seeds[0].own_samples, nullptr).c_str());
  }
  for (const SmallErrorSeedScore& s : score.seeds) {
    AppendF(&text, "damaged samples missed (seed %u):%s\n", s.seed,
            runs(s.damaged_samples, &s.flagged_samples).c_str());
  }
  return text;
}

// --method=repair's console table (the thesis' Table 1): each method's mean over the trials.
std::string RepairTable(const MarkerTake& take, const EvaluateConfig& config, const EvaluateResult& result) {
  std::string text;
  const std::vector<RepairEvaluationRow>& mean_rows = result.mean_rows;
  const double cm = take.skeleton.unit().metres_per_unit * 100.0, mm = cm * 10.0;
  AppendF(&text, "%d frames, %d markers, %d trial(s); errors against the solve of the clean markers\n",
          static_cast<int>(take.observed.size()), take.markers.num_markers(), config.evaluate.trials);
  AppendF(&text,
          "| method | joint pos (cm) | joint rot (deg) | damaged markers mean / RMS / max (mm) | covered "
          "| velocity jump (mm/frame) | time (s) |\n|---|---|---|---|---|---|---|\n");
  for (const RepairEvaluationRow& r : mean_rows) {
    AppendF(&text, "| %s | %.3f | %.3f | %.2f / %.2f / %.1f | %.1f %% | %.3f | %.3f |\n", r.method.c_str(),
            r.joint_position_error * cm, r.joint_rotation_error * kDegreesPerRadian, r.marker_error_mean * mm,
            r.marker_error_rms * mm, r.marker_error_max * mm,
            r.damaged_samples > 0 ? 100.0 * r.covered_samples / r.damaged_samples : 100.0, r.velocity_jump * mm,
            r.seconds);
  }
  // Per damage kind present: each method's mean error on it, and the share it detected
  // (changed; for gaps, filled), then the precision of all it changed.
  std::string kinds;
  for (int k = 0; k < kNumDamageKinds; ++k) {
    if (mean_rows.empty() || mean_rows.back().kind_samples[k] == 0) continue;
    kinds += std::string(kinds.empty() ? "" : " | ") + kDamageKindNames[k];
  }
  AppendF(&text, "damaged-marker mean error (mm) and recall by kind: %s; precision of all changed samples\n",
          kinds.c_str());
  for (const RepairEvaluationRow& r : mean_rows) {
    if (r.method == "clean") continue;
    AppendF(&text, "  %-15s", r.method.c_str());
    for (int k = 0; k < kNumDamageKinds; ++k) {
      if (r.kind_samples[k] == 0) continue;
      AppendF(&text, " %7.2f %5.1f%%", r.kind_error[k] * mm, 100.0 * r.Recall(k));
    }
    AppendF(&text, "   precision %.1f%% (%d changed)\n", 100.0 * r.Precision(), r.changed_samples);
  }
  const int unlabelled = DamageKindIndex('u');
  if (!mean_rows.empty() && mean_rows.back().kind_samples[unlabelled] > 0) {
    const RepairEvaluationRow& r = mean_rows.back();
    AppendF(&text,
            "unlabelled samples (ours): %d of %d assigned to their own marker (%.1f%%), %d to another; %d "
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
    AppendF(&text, "joint position error of each method / ours:");
    for (const RepairEvaluationRow& r : mean_rows) {
      if (r.method == "clean" || r.method == "ours") continue;
      AppendF(&text, " %s %.1fx", r.method.c_str(), r.joint_position_error / ours->joint_position_error);
    }
    AppendF(&text, "\n");
  }
  return text;
}

}  // namespace

std::string EvaluateSummary(const MarkerTake& take, const EvaluateConfig& config, const EvaluateResult& result) {
  if (config.method == "leave_one_out") return LeaveOneOutTable(take, config, result);
  if (config.method == "small_errors") return SmallErrorsTable(take, config, result);
  if (config.method == "repair") return RepairTable(take, config, result);
  return "";
}

}  // namespace mocapsolve
