#include "pipeline/take_view.h"

#include <algorithm>
#include <cmath>

#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "viewer/repair_intervals.h"

namespace mocapsolve {
namespace {

std::vector<ReportedInterval> Reported(const std::vector<RepairInterval>& intervals) {
  std::vector<ReportedInterval> out;
  for (const RepairInterval& i : intervals) out.push_back({i.marker, i.first, i.last, i.what});
  return out;
}

}  // namespace

std::vector<ViewInterval> RepairViewIntervals(const RepairReport& report) {
  return RepairedViewIntervals(Reported(report.detected), Reported(report.filled));
}

double TakeMarkerRmsMm(const TakeViewInputs& inputs, int* samples) {
  const auto* shown = inputs.repaired != nullptr ? inputs.repaired : inputs.observed;
  double sum_sq = 0.0;
  int total = 0;
  if (inputs.skeleton != nullptr && inputs.markers != nullptr && inputs.motion != nullptr && shown != nullptr) {
    const int frames = std::min<int>(inputs.motion->num_frames(), static_cast<int>(shown->size()));
    for (int f = 0; f < frames; ++f) {
      int count = 0;
      const double rms = RmsMarkerError(*inputs.skeleton, *inputs.markers, inputs.motion->frames[f], (*shown)[f], &count);
      sum_sq += rms * rms * count;
      total += count;
    }
  }
  if (samples != nullptr) *samples = total;
  const double mm = inputs.skeleton != nullptr ? inputs.skeleton->unit().metres_per_unit * 1000.0 : 0.0;
  return total > 0 ? std::sqrt(sum_sq / total) * mm : 0.0;
}

Status TakeViewTransform(const TakeViewInputs& inputs, ViewTransform* transform) {
  if (inputs.skeleton == nullptr) return Status::Error("view: no skeleton");
  const auto* shown = inputs.repaired != nullptr ? inputs.repaired : inputs.observed;
  // Up axis from the solved joints, else from the markers.
  std::vector<std::vector<Eigen::Vector3d>> points;
  if (inputs.motion != nullptr && inputs.motion->num_frames() > 0) {
    points = ClipJointPositions(*inputs.skeleton, *inputs.motion);
  } else if (shown != nullptr) {
    points = *shown;
  }
  // A subject's skeleton has a known unit, so no height is needed for a guess.
  return MakeViewTransform("skeleton", GuessUpAxis(points), inputs.skeleton->unit(), 0.0, transform);
}

Status MakeTakeViewScene(const TakeViewInputs& inputs, ViewScene* scene) {
  if (inputs.skeleton == nullptr) return Status::Error("view: no skeleton");
  const Skeleton& skeleton = *inputs.skeleton;
  const auto* shown = inputs.repaired != nullptr ? inputs.repaired : inputs.observed;
  if (shown != nullptr && inputs.markers == nullptr) return Status::Error("view: markers without a marker set");
  if (!(inputs.frame_rate > 0.0)) return Status::Error("view: the take's frame rate is not positive");

  ViewTransform transform;
  Status status = TakeViewTransform(inputs, &transform);
  if (!status.ok()) return status;

  ViewScene out;
  out.title = inputs.title;
  out.frame_rate = inputs.frame_rate;
  out.notes.push_back(transform.note);
  if (shown != nullptr) {
    std::vector<std::string> labels;
    for (int m = 0; m < inputs.markers->num_markers(); ++m) labels.push_back(inputs.markers->label(m));
    ViewMarkers markers = MakeViewMarkers("markers", labels, *shown, transform);
    MarkRepairedSamples(inputs.intervals, &markers);
    out.markers.push_back(std::move(markers));
    out.intervals = inputs.intervals;
  }
  if (inputs.motion != nullptr && inputs.motion->num_frames() > 0) {
    out.skeletons.push_back(MakeViewSkeleton("solved skeleton", skeleton, *inputs.motion, transform));
    if (shown != nullptr) {
      ViewCurve residual;
      residual.name = "marker residual (RMS)";
      residual.unit = "mm";
      const double mm = skeleton.unit().metres_per_unit * 1000.0;
      const int frames = std::min<int>(inputs.motion->num_frames(), static_cast<int>(shown->size()));
      residual.values.assign(frames, std::nanf(""));
      for (int f = 0; f < frames; ++f) {
        int count = 0;
        const double rms = RmsMarkerError(skeleton, *inputs.markers, inputs.motion->frames[f], (*shown)[f], &count);
        if (count > 0) residual.values[f] = static_cast<float>(rms * mm);
      }
      out.curves.push_back(std::move(residual));
    }
  }
  out.characters = inputs.characters;
  *scene = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
