// mocapsolve repair: find broken marker intervals against a robust kinematic reference
// and refill them (thesis chapter 3; problems/marker_repair/marker_repair.h).
#include <cstdio>
#include <memory>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/progress.h"
#include "apps/repair_flags.h"
#include "apps/solver_flags.h"
#include "apps/view_flags.h"
#include "settings/view_page_settings.h"
#include "io/bvh_writer.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "pipeline/take_view.h"
#include "tasks/repair_task.h"


namespace mocapsolve {
namespace {

// The console summary: what was found and filled, the unlabelled points assigned, and the
// time of each stage.
void PrintRepairSummary(const MarkerTake& take, const RepairResult& result) {
  const RepairReport& report = result.details;
  const double mm = take.skeleton.unit().metres_per_unit * 1000.0;
  std::printf("repair: %zu swaps undone, %zu intervals detected, %zu filled (%d samples trimmed, %d in small tracks "
              "dropped, %d by polynomial); RMS marker residual naive %.3g mm, reference %.3g mm, "
              "repaired %.3g mm (%d frames re-solved)\n",
              report.swaps.size(), report.detected.size(), report.filled.size(), report.trimmed_samples,
              report.removed_track_samples, report.polynomial_samples, report.naive_rms * mm,
              report.reference_rms * mm, report.repaired_rms * mm, report.resolved_frames);
  if (take.unlabelled.num_tracks() > 0) {
    int points = 0;
    for (const auto& frame : take.unlabelled.points) {
      for (const Eigen::Vector3d& p : frame) points += p.allFinite();
    }
    std::printf("  unlabelled points: %d in %d tracks; %d assigned to missing markers in %zu runs%s\n", points,
                take.unlabelled.num_tracks(), result.unlabelled_removed_samples, report.unlabelled.size(),
                report.unlabelled.empty() ? "" : ":");
    for (const UnlabelledAssignment& a : report.unlabelled) {
      std::printf("    %s <- %s frames %d-%d (%d), mean %.3g mm from the prediction\n",
                  take.markers.label(a.marker).c_str(), take.unlabelled.names[a.track].c_str(), a.first, a.last,
                  a.last - a.first + 1, a.mean_distance * mm);
    }
  }
  double total = 0.0;
  for (const RepairStageTime& t : report.timings) total += t.seconds;
  for (const RepairStageTime& t : report.timings) {
    std::printf("  %-30s %8.3f s  %5.1f %%\n", t.stage.c_str(), t.seconds, total > 0 ? 100 * t.seconds / total : 0.0);
  }
  std::printf("  %-30s %8.3f s  (%.0f frames/s)\n", "total", total, total > 0 ? take.observed.size() / total : 0.0);
}

Status RepairMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  std::vector<std::string> inputs;
  Status checked = MarkerTakeInputs(&inputs);
  if (!checked.ok()) return checked;
  if (Files().out_markers.empty()) return Status::Error("--out_markers is required");
  for (const std::string& out : {Files().out_markers, Files().out_motion}) {
    if (out.empty()) continue;
    for (const std::string& in : inputs) {
      Status status = CheckNotAnInput(out, in);
      if (!status.ok()) return status;
    }
  }
  checked = CheckViewFlag(inputs);
  if (!checked.ok()) return checked;
  if (!IsMarkerFile(Files().out_markers)) return Status::Error(Files().out_markers + ": expected .c3d or .trc");
  if (!Files().out_motion.empty() && !IsTextOutputPath(Files().out_motion, ".bvh")) {
    return Status::Error(Files().out_motion + ": expected a .bvh");
  }
  MarkerTake take;
  SetStage("inputs");
  Status status = LoadMarkerTake(&take);
  if (!status.ok()) return status;
  RepairConfig config;
  config.repair = RepairSettingsFromFlags();
  config.solver = SolverSettingsFromFlags();
  std::unique_ptr<Progress> progress;
  std::string progress_stage;
  const RepairProgress show_progress = [&](const std::string& stage, int done, int total) {
    if (stage != progress_stage) {
      progress_stage = stage;
      progress = std::make_unique<Progress>("repair: " + stage, total, Console().quiet);
    }
    progress->Update(done);
  };
  SetStage("repair");
  RepairResult result;
  status = RunRepair(take, config, show_progress, &result);
  if (!status.ok()) return status;

  SetStage("writing");
  status = WriteMarkerFile(Files().out_markers, result.markers);
  if (!status.ok()) return status;
  if (!Files().out_motion.empty()) {
    status = WriteBvh(Files().out_motion, take.skeleton, result.motion, BvhWriteOptions());
    if (!status.ok()) return status;
  }
  PrintRepairSummary(take, result);
  std::printf("wrote %s\n", Files().out_markers.c_str());
  JsonObject json;
  json.Add("markers", Files().markers).Add("out_markers", Files().out_markers).Merge(result.report);
  status = WriteViewFlag([&](ViewScene* scene) {
    TakeViewInputs view;
    view.title = "repair: " + FileStem(Files().markers);
    view.skeleton = &take.skeleton;
    view.markers = &take.markers;
    view.observed = &take.observed;
    view.repaired = &result.repaired;
    view.intervals = RepairViewIntervals(result.details);
    view.motion = &result.motion;
    view.frame_rate = result.motion.frame_rate > 0 ? result.motion.frame_rate : 30.0;
    return MakeTakeViewScene(view, scene);
  });
  if (!status.ok()) return status;
  return WriteReport(json);
}

}  // namespace

extern const Command kRepairCommand = {
    "repair", "find broken marker intervals against a robust reference and refill them",
    "mocapsolve repair (--skeleton=S --markerset=J.json | --subject=S.json) --markers=IN.c3d|.trc "
    "--out_markers=OUT.c3d|.trc [--out_motion=OUT.bvh] [--report=r.json] [--view=PAGE.html]\n\n"
    "Thesis chapter 3: a naive per-frame solve and a robust reference (--reference: a robust\n"
    "tracker or the whole-clip solve; Cauchy loss); marker paths rebuilt from the\n"
    "reference; gaps = missing samples, outliers and joints that differ from the reference (--dp_max_cm, --dr_max_deg);\n"
    "unlabelled points (C3D '*52') assigned to missing markers where the reference predicts them\n"
    "(--assign_unlabelled; they leave their unlabelled columns in --out_markers);\n"
    "trimming, small tracks and small gaps; Hermite refill from the reference; re-solve.\n"
    "Samples never marked bad are written as they were read. Prints per-stage timings.",
    __FILE__, RepairMain,
    {SharedOptions("subject,skeleton,skeleton_units,markers,markerset,axes,marker_scale,out_markers,out_motion,report"),
     RepairSettingOptions().options(), RepairSolverOptions().options(), ViewPageOption().options()}};

}  // namespace mocapsolve
