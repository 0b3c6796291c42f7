#include "tasks/calibrate_task.h"

#include <cmath>

#include "problems/marker_solve/mean_pose.h"

namespace mocapsolve {

Status CalibrateSubject(const Skeleton& skeleton, const Motion& motion,
                        const MarkerTrajectories& file_trajectories,
                        const SubjectCalibrationOptions& options, SubjectCalibration* out) {
  if (options.min_valid_frames < 1) return Status::Error("--min_valid_frames must be >= 1");
  MarkerTrajectories trajectories = file_trajectories;
  // Marker file -> model frame: scale, then axes (given or searched).
  MarkerFileToModel transform;
  if (options.marker_scale > 0.0 && std::isfinite(options.marker_scale)) {
    transform.scale = options.marker_scale;
  } else if (options.marker_scale != 0.0) {
    return Status::Error("--marker_scale must be positive (or 0: from the units)");
  } else {
    Status status = UnitScale(trajectories.unit, skeleton.unit(), &transform.scale);
    if (!status.ok()) {
      return Status::Error(options.markers_name + ": " + status.message() + " (or --skeleton_units)");
    }
  }
  CalibrationOptions calibration;
  calibration.frame_offset = options.frame_offset;
  calibration.min_valid_frames = options.min_valid_frames;
  std::vector<double> axis_rms;
  if (options.axes == "auto") {
    MarkerTrajectories scaled = trajectories;
    MarkerFileToModel scale_only;
    scale_only.scale = transform.scale;
    TransformMarkers(scale_only, skeleton.unit(), &scaled);
    Status status = FindMarkerAxes(skeleton, motion, scaled, calibration, options.attachments,
                                   &transform.rotation, &axis_rms);
    if (!status.ok()) return Status::Error(options.markers_name + ": " + status.message());
  } else {
    Status status = ParseAxes(options.axes, &transform.rotation);
    if (!status.ok()) return status;
  }
  TransformMarkers(transform, skeleton.unit(), &trajectories);
  SubjectCalibration result;
  Status status = CalibrateMarkers(skeleton, motion, trajectories, calibration, options.attachments,
                                   &result.result);
  if (!status.ok()) return Status::Error(options.markers_name + ": " + status.message());
  Subject& subject = result.subject;
  subject.skeleton = skeleton;
  subject.skeleton_path = options.skeleton_path;
  subject.markers = result.result.marker_set;
  subject.axes = AxesName(transform.rotation);
  subject.marker_scale = options.marker_scale;
  if (trajectories.subject_prefixes.size() == 1) subject.label_prefix = trajectories.subject_prefixes[0];
  subject.amc_fps = options.amc_fps;
  subject.mean_pose = MeanPose(skeleton, motion);  // The rest prior's reference.
  result.transform = transform;
  result.axis_rms = std::move(axis_rms);
  *out = std::move(result);
  return Status::Ok();
}

}  // namespace mocapsolve
