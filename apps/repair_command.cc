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
#include "io/bvh_writer.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "pipeline/take_view.h"
#include "problems/marker_repair/marker_repair.h"

DEFINE_string(out_markers, "", "Repaired markers (.c3d or .trc), in the input file's axes and units.");
DEFINE_string(out_motion, "", "The motion solved from the repaired markers (.bvh); optional.");

namespace mocapsolve {
namespace {

Status RunRepair(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  std::vector<std::string> inputs;
  Status checked = MarkerTakeInputs(&inputs);
  if (!checked.ok()) return checked;
  if (FLAGS_out_markers.empty()) return Status::Error("--out_markers is required");
  for (const std::string& out : {FLAGS_out_markers, FLAGS_out_motion}) {
    if (out.empty()) continue;
    for (const std::string& in : inputs) {
      Status status = CheckNotAnInput(out, in);
      if (!status.ok()) return status;
    }
  }
  checked = CheckViewFlag(inputs);
  if (!checked.ok()) return checked;
  if (!IsMarkerFile(FLAGS_out_markers)) return Status::Error(FLAGS_out_markers + ": expected .c3d or .trc");
  if (!FLAGS_out_motion.empty() && !IsTextOutputPath(FLAGS_out_motion, ".bvh")) {
    return Status::Error(FLAGS_out_motion + ": expected a .bvh");
  }
  MarkerTake take;
  SetStage("inputs");
  Status status = LoadMarkerTake(&take);
  if (!status.ok()) return status;
  const Skeleton& skeleton = take.skeleton;
  const MarkerSet& markers = take.markers;
  const MarkerTrajectories& trajectories = take.trajectories;
  const auto& observed = take.observed;

  RepairOptions options;
  status = RepairOptionsFromFlags(skeleton, &options);
  if (!status.ok()) return status;
  SetRepairRestRotations(take.mean_pose, &options);

  std::vector<std::vector<Eigen::Vector3d>> repaired;
  Motion motion;
  RepairReport report;
  std::unique_ptr<Progress> progress;
  std::string progress_stage;
  const RepairProgress show_progress = [&](const std::string& stage, int done, int total) {
    if (stage != progress_stage) {
      progress_stage = stage;
      progress = std::make_unique<Progress>("repair: " + stage, total, FLAGS_quiet);
    }
    progress->Update(done);
  };
  SetStage("repair");
  status = RepairMarkers(skeleton, markers, observed, take.unlabelled, options, &repaired, &motion, &report, nullptr,
                         show_progress);
  if (!status.ok()) return Status::Error(FLAGS_markers + ": " + status.message());
  motion.frame_rate = trajectories.frame_rate;

  // Output: the input file with the repaired samples, in its own axes and units.
  // Points assigned to markers leave their unlabelled columns.
  int unlabelled_removed = 0;
  const MarkerTrajectories out = WithRepairedSamples(take, repaired, nullptr, report.unlabelled, &unlabelled_removed);
  SetStage("writing");
  status = WriteMarkerFile(FLAGS_out_markers, out);
  if (!status.ok()) return status;
  if (!FLAGS_out_motion.empty()) {
    status = WriteBvh(FLAGS_out_motion, skeleton, motion, BvhWriteOptions());
    if (!status.ok()) return status;
  }
  const double mm = skeleton.unit().metres_per_unit * 1000.0;
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
                take.unlabelled.num_tracks(), unlabelled_removed, report.unlabelled.size(),
                report.unlabelled.empty() ? "" : ":");
    for (const UnlabelledAssignment& a : report.unlabelled) {
      std::printf("    %s <- %s frames %d-%d (%d), mean %.3g mm from the prediction\n", markers.label(a.marker).c_str(),
                  take.unlabelled.names[a.track].c_str(), a.first, a.last, a.last - a.first + 1, a.mean_distance * mm);
    }
  }
  double total = 0.0;
  for (const RepairStageTime& t : report.timings) total += t.seconds;
  for (const RepairStageTime& t : report.timings) {
    std::printf("  %-30s %8.3f s  %5.1f %%\n", t.stage.c_str(), t.seconds, total > 0 ? 100 * t.seconds / total : 0.0);
  }
  std::printf("  %-30s %8.3f s  (%.0f frames/s)\nwrote %s\n", "total", total,
              total > 0 ? observed.size() / total : 0.0, FLAGS_out_markers.c_str());
  auto intervals = [&](const std::vector<RepairInterval>& list) {
    std::vector<JsonObject> json;
    for (const RepairInterval& i : list) {
      JsonObject o;
      o.Add("marker", markers.label(i.marker)).Add("first_frame", i.first).Add("last_frame", i.last).Add("what", i.what);
      json.push_back(o);
    }
    return json;
  };
  std::vector<JsonObject> swaps;
  for (const MarkerSwap& swap : report.swaps) {
    std::vector<JsonObject> renamed;
    for (const auto& [from, to] : swap.from_to) {
      JsonObject o;
      o.Add("from", markers.label(from)).Add("to", markers.label(to));
      renamed.push_back(o);
    }
    JsonObject o;
    o.Add("first_frame", swap.first).Add("last_frame", swap.last).Add("markers_renamed_from_to", renamed)
        .Add("mean_distance_before_mm", swap.distance_before * mm).Add("mean_distance_after_mm", swap.distance_after * mm);
    swaps.push_back(o);
  }
  const std::vector<JsonValue> track_names(take.unlabelled.names.begin(), take.unlabelled.names.end());
  std::vector<JsonObject> assigned;
  for (const UnlabelledAssignment& a : report.unlabelled) {
    JsonObject o;
    o.Add("marker", markers.label(a.marker)).Add("unlabelled", take.unlabelled.names[a.track])
        .Add("first_frame", a.first).Add("last_frame", a.last).Add("frames", a.last - a.first + 1)
        .Add("mean_distance_mm", a.mean_distance * mm);
    assigned.push_back(o);
  }
  std::vector<JsonObject> timings;
  for (const RepairStageTime& t : report.timings) {
    JsonObject o;
    o.Add("stage", t.stage).Add("seconds", t.seconds);
    timings.push_back(o);
  }
  JsonObject json;
  json.Add("markers", FLAGS_markers).Add("out_markers", FLAGS_out_markers).Add("frames", static_cast<int>(observed.size()))
      .Add("swaps", swaps).Add("unlabelled_tracks", track_names).Add("unlabelled_assigned", assigned)
      .Add("unlabelled_removed_samples", unlabelled_removed).Add("detected", intervals(report.detected)).Add("filled", intervals(report.filled))
      .Add("timings", timings).Add("rms_naive_mm", report.naive_rms * mm)
      .Add("rms_reference_mm", report.reference_rms * mm).Add("rms_repaired_mm", report.repaired_rms * mm)
      .Add("resolved_frames", report.resolved_frames).Add("reference", RepairSettingsFromFlags().reference);
  status = WriteViewFlag([&](ViewScene* scene) {
    TakeViewInputs view;
    view.title = "repair: " + FileStem(FLAGS_markers);
    view.skeleton = &skeleton;
    view.markers = &markers;
    view.observed = &observed;
    view.repaired = &repaired;
    view.intervals = RepairViewIntervals(report);
    view.motion = &motion;
    view.frame_rate = motion.frame_rate > 0 ? motion.frame_rate : 30.0;
    return MakeTakeViewScene(view, scene);
  });
  if (!status.ok()) return status;
  return WriteReport(json);
}

const char kRepairFlags[] = "subject,skeleton,skeleton_units,markers,markerset,axes,marker_scale,report,quiet,view";

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
    __FILE__, RunRepair, kRepairFlags, {RepairSettingOptions().options(), RepairSolverOptions().options()}};

}  // namespace mocapsolve
