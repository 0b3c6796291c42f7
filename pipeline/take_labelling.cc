#include "pipeline/take_labelling.h"

#include <algorithm>
#include <chrono>

#include "io/marker_file.h"
#include "problems/marker_solve/marker_observations.h"

namespace mocapsolve {
namespace {

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

}  // namespace

Status LabelTakeForSubject(const Subject& subject, const MarkerTrajectories& file, const std::string& name,
                           const LabelSettings& settings, const SolverSettings& solver,
                           const LabelProgress& progress, TakeLabelling* labelling) {
  Status status = RequireMarkerData(name, file);
  if (!status.ok()) return status;
  MarkerFileToModel transform;
  status = SubjectFileTransform(subject, file, name, &transform);
  if (!status.ok()) return status;
  MarkerSolveOptions solve;
  status = MarkerSolveOptionsFromSettings(solver, subject.skeleton, subject.mean_pose, &solve);
  if (!status.ok()) return status;
  LabellerOptions options;
  status = LabellerOptionsFromSettings(settings, subject.skeleton.unit(), solve, &options);
  if (!status.ok()) return status;
  std::vector<std::vector<Eigen::Vector3d>> cloud(file.num_frames());
  std::vector<std::vector<int>> column(file.num_frames());
  TakeLabelling out;
  for (int f = 0; f < file.num_frames(); ++f) {
    for (int c = 0; c < file.num_markers(); ++c) {
      if (!file.valid(f, c)) continue;
      cloud[f].push_back(transform.Apply(file.position(f, c)));
      column[f].push_back(c);
      ++out.points;
    }
  }
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
  *labelling = std::move(out);
  return Status::Ok();
}

JsonObject LabellingReport(const Subject& subject, const TakeLabelling& labelling) {
  const LabellingResult& d = labelling.details;
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
  const int frames = labelling.markers.num_frames();
  const double fps = labelling.seconds > 0 ? frames / labelling.seconds : 0.0;
  std::vector<JsonValue> acquisitions(d.acquisitions.begin(), d.acquisitions.end());
  const double mm = subject.skeleton.unit().metres_per_unit * 1000.0;
  return JsonObject()
      .Add("frames", frames)
      .Add("points", labelling.points)
      .Add("samples_labelled", labelled)
      .Add("points_left_unlabelled", labelling.points - labelled)
      .Add("swaps_avoided", swaps)
      .Add("reacquisitions", reacquired)
      .Add("low_confidence_left", refused)
      .Add("body_acquisition_frames", acquisitions)
      .Add("first_acquisition",
           JsonObject().Add("frame", d.first_frame).Add("markers_matched", d.first.matched).Add("rms_mm", d.first.rms * mm))
      .Add("frames_without_body", d.lost_frames)
      .Add("seconds", labelling.seconds)
      .Add("frames_per_second", fps)
      .Add("per_label", per_label);
}

std::vector<std::string> SubjectLabelsMissing(const Subject& subject, const MarkerTrajectories& file) {
  std::vector<std::string> missing;
  for (int m = 0; m < subject.markers.num_markers(); ++m) {
    const std::string& label = subject.markers.label(m);
    if (file.FindMarker(label) < 0 && file.FindMarker(subject.label_prefix + label) < 0) missing.push_back(label);
  }
  return missing;
}

}  // namespace mocapsolve
