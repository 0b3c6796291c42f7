#include "tasks/repair_task.h"

#include <string>

#include "pipeline/repair_report.h"

namespace mocapsolve {
namespace {

std::vector<JsonObject> IntervalsJson(const std::vector<RepairInterval>& intervals, const MarkerSet& markers) {
  std::vector<JsonObject> json;
  for (const RepairInterval& i : intervals) {
    JsonObject o;
    o.Add("marker", markers.label(i.marker)).Add("marker_index", i.marker).Add("first_frame", i.first)
        .Add("last_frame", i.last).Add("what", i.what);
    json.push_back(o);
  }
  return json;
}

JsonObject RepairReportJson(const MarkerTake& take, const RepairConfig& config, const RepairResult& result) {
  const MarkerSet& markers = take.markers;
  const RepairReport& report = result.details;
  const double mm = take.skeleton.unit().metres_per_unit * 1000.0;
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
  json.Add("frames", static_cast<int>(take.observed.size())).Add("swaps", swaps).Add("unlabelled_tracks", track_names)
      .Add("unlabelled_assigned", assigned).Add("unlabelled_removed_samples", result.unlabelled_removed_samples)
      .Add("detected", IntervalsJson(report.detected, markers)).Add("filled", IntervalsJson(report.filled, markers))
      .Add("carried_joints", CarriedJointsJson(take.skeleton, report.carried))
      .Add("naive_hidden_joints_held_frames", HeldJointsJson(take.skeleton, report.naive_held_frames))
      .Add("naive_twist_held_frames", HeldJointsJson(take.skeleton, report.naive_twist_held_frames))
      .Add("timings", timings).Add("rms_naive_mm", report.naive_rms * mm)
      .Add("rms_reference_mm", report.reference_rms * mm).Add("rms_repaired_mm", report.repaired_rms * mm)
      .Add("resolved_frames", report.resolved_frames).Add("reference", config.repair.reference)
      .Add("trimmed_samples", report.trimmed_samples).Add("removed_track_samples", report.removed_track_samples)
      .Add("polynomial_samples", report.polynomial_samples).Add("rewritten_samples", result.rewritten_samples);
  return json;
}

}  // namespace

Status RepairOptionsForTake(const MarkerTake& take, const RepairConfig& config, RepairOptions* options) {
  Status status = RepairOptionsFromSettings(config.repair, config.solver, take.skeleton, options);
  if (!status.ok()) return status;
  SetRepairRestRotations(take.mean_pose, options);
  return Status::Ok();
}

Status RunRepair(const MarkerTake& take, const RepairConfig& config, const RepairProgress& progress,
                 RepairResult* result) {
  RepairOptions options;
  Status status = RepairOptionsForTake(take, config, &options);
  if (!status.ok()) return status;
  *result = RepairResult();
  status = RepairMarkers(take.skeleton, take.markers, take.observed, take.unlabelled, options, &result->repaired,
                         &result->motion, &result->details, nullptr, progress);
  if (!status.ok()) return Status::Error(take.name + ": " + status.message());
  result->motion.frame_rate = take.trajectories.frame_rate;
  // Points assigned to markers leave their unlabelled columns.
  result->markers = WithRepairedSamples(take, result->repaired, &result->rewritten_samples, result->details.unlabelled,
                                        &result->unlabelled_removed_samples);
  result->report = RepairReportJson(take, config, *result);
  return Status::Ok();
}

}  // namespace mocapsolve
