// mocapsolve evaluate: marker repair against the usual gap fills on the same damage, the
// analogue of the thesis' Table 1 (problems/marker_repair/repair_evaluation.h).
#include <cstdio>
#include <memory>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "apps/corruption_flags.h"
#include "apps/progress.h"
#include "apps/repair_flags.h"
#include "apps/solver_flags.h"
#include "settings/method_settings.h"
#include "io/atomic_file.h"
#include "tasks/leave_one_out_protocol.h"
#include "tasks/evaluate_summary.h"
#include "tasks/evaluate_retarget_task.h"
#include "tasks/evaluate_task.h"
#include "pipeline/quality_gate.h"
#include "settings/frame_limit_settings.h"
#include "settings/retarget_settings.h"
#include "settings/skeleton_fit_settings.h"


namespace mocapsolve {
namespace {

// --method=retarget: --motion onto each of --target (comma-separated), a row each.
Status EvaluateRetarget() {
  EvaluateRetargetInputs inputs;
  inputs.source = Files().motion;
  inputs.skeleton = Files().skeleton;
  inputs.amc_fps = FileReading().amc_fps;
  FrameLimitSettings limit;
  ReadOptionFlags(FrameLimitOption(), &limit);
  inputs.max_frames = limit.max_frames;
  inputs.characters = SplitCharacterList(Files().target);
  QualityGate gate;
  ReadOptionFlags(QualityGateOptions().Only(RetargetGateNames()), &gate);
  Progress progress("evaluate retarget", static_cast<int>(inputs.characters.size()), Console().quiet, "characters");
  RetargetSettings retarget = RetargetSettingOptions().Defaults();
  ReadOptionFlags(RetargetSettingOptions(), &retarget);  // The retarget's knobs (not --solver: dls).
  EvaluateRetargetResult result;
  Status status = RunEvaluateRetarget(inputs, retarget, gate,
                                      [&](int done, int) { progress.Update(done); }, &result);
  if (!status.ok()) return status;
  std::fputs(result.table.c_str(), stdout);
  if (!Files().table_csv.empty()) {
    status = WriteFileAtomically(Files().table_csv, result.table_csv);
    if (!status.ok()) return status;
  }
  return WriteReport(result.report);
}

Status EvaluateMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  MethodSetting method;
  ReadOptionFlags(EvaluateMethodOption(), &method);
  if (method.method == "retarget") return EvaluateRetarget();
  std::vector<std::string> inputs;
  Status checked = MarkerTakeInputs(&inputs);
  if (!checked.ok()) return checked;
  EvaluateConfig config;
  config.method = method.method;
  ReadOptionFlags(EvaluateSettingOptions(), &config.evaluate);
  config.repair = RepairSettingsFromFlags();
  config.solver = SolverSettingsFromFlags();
  config.damage = CorruptionSettingsFromFlags();
  ReadOptionFlags(SkeletonFitSettingOptions(), &config.fit);
  if (!Files().table_csv.empty()) {
    for (const std::string& in : inputs) {
      Status status = CheckNotAnInput(Files().table_csv, in);
      if (!status.ok()) return status;
    }
  }
  MarkerTake take;
  Status status = config.method == "leave_one_out" && config.evaluate.protocol == "time_split"
                      ? ReadTimeSplitTake(Files().subject, Files().markers,
                                          GivenOnCommandLine("axes") ? &FileReading().axes : nullptr,
                                          GivenOnCommandLine("marker_scale") ? &FileReading().marker_scale : nullptr,
                                          &take)
                      : LoadMarkerTake(&take);
  if (!status.ok()) return status;
  std::unique_ptr<Progress> progress;
  if (config.method == "leave_one_out") {
    const bool split = config.evaluate.protocol == "time_split";  // Then the fitted subject's markers.
    progress = std::make_unique<Progress>("leave one out (" + config.solver.solver + ", " + config.solver.mode + ")",
                                          split ? take.trajectories.num_markers() : take.markers.num_markers(),
                                          Console().quiet, "markers");
  } else if (config.method == "repair") {
    progress = std::make_unique<Progress>("evaluate", config.evaluate.trials, Console().quiet, "trials");
  }
  EvaluateResult result;
  status = RunEvaluate(take, config, [&](int done, int) { if (progress) progress->Update(done); }, &result);
  if (!status.ok()) return status;
  std::fputs(EvaluateSummary(take, config, result).c_str(), stdout);
  if (!Files().table_csv.empty() && !result.table_csv.empty()) {
    status = WriteFileAtomically(Files().table_csv, result.table_csv);
    if (!status.ok()) return status;
  }
  JsonObject report;
  report.Add("markers", Files().markers).Merge(result.report);
  return WriteReport(report);
}

}  // namespace

extern const Command kEvaluateCommand = {
    "evaluate", "score marker repair against linear, polynomial, PCA and reference-only fills",
    "mocapsolve evaluate (--skeleton=S --markerset=J.json | --subject=S.json) --markers=CLEAN.c3d|.trc [--trials=N] "
    "[--seed=1 --gaps=10 ...] [--table_csv=t.csv] [--report=r.json]\n"
    "       mocapsolve evaluate --method=leave_one_out (--subject=S.json | ...) --markers=TAKE.c3d|.trc "
    "[--mode=frame|clip] [--table_csv=t.csv]\n"
    "       mocapsolve evaluate --method=small_errors (--subject=S.json | ...) --markers=TAKE.c3d|.trc [--trials=5] "
    "[--white_noise_mm=1]\n"
    "       mocapsolve evaluate --method=retarget --motion=SRC.bvh|.amc|.fbx|.glb [--skeleton=X.asf] "
    "--target=A.glb,B.glb,... [--gate_limb_mean_deg=10 ...]\n\n"
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
    "latter also without the samples it flags on the undamaged take (the take's own glitches).\n"
    "--method=retarget retargets --motion onto each --target character (retarget's options, dls) and\n"
    "prints per character what the solve's residual cannot hide: the eight limbs' direction error\n"
    "against the source (mean, 95th percentile, after one constant rotation), planted feet's skate,\n"
    "ground penetration (the source's own beside it), the joint error where the source is the\n"
    "character's own skeleton, the fewest tracked vertices on a limb, and the gate's verdict.",
    __FILE__, EvaluateMain,
    {SharedOptions("subject,skeleton,skeleton_units,markers,markerset,axes,marker_scale,table_csv,report,motion,"
                   "target,amc_fps"),
     FrameLimitOption().options(), EvaluateSolverOptions().options(),
     SolverOptions().Only("mode").options(),  // leave_one_out's frame or clip solve.
     RepairSettingOptions().options(), CorruptionSettingOptions().options(), EvaluateSettingOptions().options(),
     EvaluateMethodOption().options(), QualityGateOptions().Only(RetargetGateNames()).options(),
     RetargetSettingOptions().options(), SkeletonFitSettingOptions().options()}};

}  // namespace mocapsolve
