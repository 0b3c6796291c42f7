#include "tasks/label_task.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "io/marker_file.h"
#include "problems/marker_solve/marker_observations.h"
#include "settings/repair_settings.h"

namespace mocapsolve {
namespace {

// The file's mapping onto the subject's skeleton (axes, then the marker scale or the units).
Status FileToSkeleton(const Subject& subject, const MarkerTrajectories& file, const std::string& name,
                      MarkerFileToModel* transform) {
  Status status = ParseAxes(subject.axes, &transform->rotation);
  if (!status.ok()) return Status::Error("axes: " + status.message());
  if (subject.marker_scale > 0.0) {
    transform->scale = subject.marker_scale;
    return Status::Ok();
  }
  status = UnitScale(file.unit, subject.skeleton.unit(), &transform->scale);
  return status.ok() ? status : Status::Error(name + ": " + status.message());
}

// The take labelled: the subject's markers, then the leftover points as "*1".."*K".
MarkerTrajectories LabelledTake(const Subject& subject, const MarkerTrajectories& file,
                                const std::vector<std::vector<int>>& marker_of_sample) {
  const int num_markers = subject.markers.num_markers();
  std::vector<std::vector<int>> leftovers(file.num_frames());
  size_t most = 0;
  for (int f = 0; f < file.num_frames(); ++f) {
    for (int c = 0; c < file.num_markers(); ++c) {
      if (file.valid(f, c) && marker_of_sample[f][c] < 0) leftovers[f].push_back(c);
    }
    most = std::max(most, leftovers[f].size());
  }
  std::vector<std::string> labels;
  for (int m = 0; m < num_markers; ++m) labels.push_back(subject.markers.label(m));
  for (size_t k = 0; k < most; ++k) labels.push_back("*" + std::to_string(k + 1));
  MarkerTrajectories out(labels, file.num_frames());
  out.frame_rate = file.frame_rate;
  out.unit = file.unit;
  out.first_frame = file.first_frame;
  for (int f = 0; f < file.num_frames(); ++f) {
    for (int c = 0; c < file.num_markers(); ++c) {
      const int m = marker_of_sample[f][c];
      if (m >= 0) out.SetSample(f, m, file.position(f, c), file.residual(f, c), file.camera_mask(f, c));
    }
    for (size_t k = 0; k < leftovers[f].size(); ++k) {
      const int c = leftovers[f][k];
      out.SetSample(f, num_markers + static_cast<int>(k), file.position(f, c), file.residual(f, c),
                    file.camera_mask(f, c));
    }
  }
  return out;
}

// The report and the console text.
void Describe(const Subject& subject, const MarkerTrajectories& file, int points, LabelResult* result) {
  const LabellingResult& d = result->details;
  std::vector<JsonObject> per_label;
  int labelled = 0, swaps = 0, reacquired = 0, refused = 0;
  for (int m = 0; m < subject.markers.num_markers(); ++m) {
    const MarkerLabelStats& s = d.per_marker[m];
    per_label.push_back(JsonObject()
                            .Add("label", subject.markers.label(m))
                            .Add("samples_labelled", s.labelled)
                            .Add("swaps_avoided", s.swaps_avoided)
                            .Add("reacquisitions", s.reacquisitions)
                            .Add("low_confidence_left", s.low_confidence));
    labelled += s.labelled, swaps += s.swaps_avoided, reacquired += s.reacquisitions, refused += s.low_confidence;
  }
  const double fps = result->seconds > 0 ? file.num_frames() / result->seconds : 0.0;
  std::vector<JsonValue> acquisitions(d.acquisitions.begin(), d.acquisitions.end());
  result->report.Add("frames", file.num_frames()).Add("points", points).Add("samples_labelled", labelled)
      .Add("points_left_unlabelled", points - labelled).Add("swaps_avoided", swaps)
      .Add("reacquisitions", reacquired).Add("low_confidence_left", refused)
      .Add("body_acquisition_frames", acquisitions)
      .Add("first_acquisition", JsonObject()
                                    .Add("frame", d.first_frame)
                                    .Add("markers_matched", d.first.matched)
                                    .Add("rms_mm", d.first.rms * subject.skeleton.unit().metres_per_unit * 1000.0)).Add("frames_without_body", d.lost_frames)
      .Add("seconds", result->seconds).Add("frames_per_second", fps).Add("per_label", per_label);
  char text[512];
  std::snprintf(text, sizeof(text),
                "label: %d frames, %d points: %d labelled (%.2f %%), %d left unlabelled (%d refused for low "
                "confidence); %d swaps avoided, %d re-acquisitions; body found at frame %d, %zu re-acquisitions "
                "of the body, %d frames without it; %.3f s (%.0f frames/s)",
                file.num_frames(), points, labelled, points > 0 ? 100.0 * labelled / points : 0.0, points - labelled,
                refused, swaps, reacquired, d.first_frame, d.acquisitions.empty() ? 0 : d.acquisitions.size() - 1,
                d.lost_frames, result->seconds, fps);
  result->summary = text;
}

}  // namespace

Status RunLabel(const Subject& subject, const MarkerTrajectories& file, const std::string& name,
                const LabelConfig& config, const LabelProgress& progress, LabelResult* result) {
  Status status = RequireMarkerData(name, file);
  if (!status.ok()) return status;
  MarkerFileToModel transform;
  status = FileToSkeleton(subject, file, name, &transform);
  if (!status.ok()) return status;
  MarkerSolveOptions solve;
  status = MarkerSolveOptionsFromSettings(config.solver, subject.skeleton, subject.mean_pose, &solve);
  if (!status.ok()) return status;
  LabellerOptions options;
  status = LabellerOptionsFromSettings(config.label, subject.skeleton.unit(), solve, &options);
  if (!status.ok()) return status;
  std::vector<std::vector<Eigen::Vector3d>> cloud(file.num_frames());
  std::vector<std::vector<int>> column(file.num_frames());
  int points = 0;
  for (int f = 0; f < file.num_frames(); ++f) {
    for (int c = 0; c < file.num_markers(); ++c) {
      if (!file.valid(f, c)) continue;
      cloud[f].push_back(transform.Apply(file.position(f, c)));
      column[f].push_back(c);
      ++points;
    }
  }
  LabelResult out;
  const auto start = std::chrono::steady_clock::now();
  status = LabelPointCloud(subject.skeleton, subject.markers, subject.mean_pose, cloud, options, progress,
                           &out.details);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!status.ok()) return Status::Error(name + ": " + status.message());
  out.marker_of_sample.assign(file.num_frames(), std::vector<int>(file.num_markers(), -1));
  for (int f = 0; f < file.num_frames(); ++f) {
    for (size_t k = 0; k < column[f].size(); ++k) out.marker_of_sample[f][column[f][k]] = out.details.marker_of_point[f][k];
  }
  out.markers = LabelledTake(subject, file, out.marker_of_sample);
  Describe(subject, file, points, &out);
  *result = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
