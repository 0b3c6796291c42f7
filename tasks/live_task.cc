#include "tasks/live_task.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "io/live_pose.h"
#include "problems/marker_solve/live_tracker.h"
#include "problems/marker_solve/marker_observations.h"

namespace mocapsolve {
namespace {

LengthUnit StreamUnit(const std::string& name) {
  return name == "m" ? Metres() : name == "cm" ? Centimetres() : Millimetres();
}

// Stream (or replayed file) positions to the skeleton's frame and units.
Status LiveTransform(const Subject& subject, const LiveFrameSource& source, const std::string& stream_units,
                     MarkerFileToModel* transform) {
  Status status = ParseAxes(subject.axes, &transform->rotation);
  if (!status.ok()) return Status::Error("subject axes: " + status.message());
  if (subject.marker_scale > 0) {
    transform->scale = subject.marker_scale;
    return Status::Ok();
  }
  const LengthUnit unit = source.unit().known() ? source.unit() : StreamUnit(stream_units);
  return UnitScale(unit, subject.skeleton.unit(), &transform->scale);
}

// Which column of a frame holds each marker of the set: a label equal to the marker's,
// or equal once the subject's label prefix, or any "Subject:" prefix, is taken off.
// Recomputed only when a frame's labels differ from the previous frame's.
class LabelMap {
 public:
  LabelMap(const MarkerSet& markers, std::string prefix) : markers_(markers), prefix_(std::move(prefix)) {}

  const std::vector<int>& Columns(const std::vector<std::string>& labels) {
    if (labels == labels_ && !columns_.empty()) return columns_;
    labels_ = labels;
    std::unordered_map<std::string, int> index;
    for (int c = static_cast<int>(labels.size()) - 1; c >= 0; --c) {
      std::string label = labels[c];
      if (!prefix_.empty() && label.compare(0, prefix_.size(), prefix_) == 0) label = label.substr(prefix_.size());
      index[label] = c;
      const size_t colon = label.rfind(':');
      if (colon != std::string::npos) index.emplace(label.substr(colon + 1), c);
    }
    for (int c = static_cast<int>(labels.size()) - 1; c >= 0; --c) index[labels[c]] = c;  // Exact wins.
    columns_.assign(markers_.num_markers(), -1);
    for (int m = 0; m < markers_.num_markers(); ++m) {
      const auto found = index.find(markers_.label(m));
      if (found != index.end()) columns_[m] = found->second;
    }
    return columns_;
  }

 private:
  const MarkerSet& markers_;
  std::string prefix_;
  std::vector<std::string> labels_;
  std::vector<int> columns_;
};

double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t rank = static_cast<size_t>(std::ceil(p * values.size()));
  return values[std::min(values.size() - 1, rank > 0 ? rank - 1 : 0)];
}

void FillReport(const Subject& subject, const LiveConfig& config, double seconds, double sum_sq, long samples,
                LiveResult* result) {
  const Skeleton& skeleton = subject.skeleton;
  const double to_mm = skeleton.unit().metres_per_unit * 1000.0;
  JsonObject latency;
  latency.Add("median", Percentile(result->latency_ms, 0.5)).Add("p99", Percentile(result->latency_ms, 0.99))
      .Add("max", result->latency_ms.empty() ? 0.0 : *std::max_element(result->latency_ms.begin(),
                                                                         result->latency_ms.end()))
      .Add("unit", "ms");
  result->report.Add("input", config.live.input).Add("output", config.live.output)
      .Add("output_format", config.live.output_format).Add("solver", config.solver.solver)
      .Add("frames_in", static_cast<double>(result->frames_in))
      .Add("frames_out", static_cast<double>(result->frames_out))
      .Add("frames_dropped", static_cast<double>(result->frames_dropped))
      .Add("bad_frames", static_cast<double>(result->bad_frames))
      .Add("unsolved_frames", static_cast<double>(result->unsolved_frames))
      .Add("predicted_samples", static_cast<double>(result->predicted_samples))
      .Add("end", result->end).Add("latency_ms", latency).Add("seconds", seconds)
      .Add("frames_per_second", seconds > 0 ? result->frames_out / seconds : 0.0)
      .Add("rms_marker_residual", samples > 0 ? std::sqrt(sum_sq / samples) * to_mm : 0.0)
      .Add("residual_unit", "mm");
}

}  // namespace

Status RunLive(const Subject& subject, const LiveConfig& config, const LiveIo& io, LiveResult* result) {
  *result = LiveResult();
  const Skeleton& skeleton = subject.skeleton;
  if (!skeleton.unit().known()) return Status::Error("the subject's skeleton unit is unknown");
  Status status = LiveSettingOptions().Validate(config.live);
  if (!status.ok()) return status;
  MarkerSolveOptions options;
  status = MarkerSolveOptionsFromSettings(config.solver, skeleton, subject.mean_pose, &options);
  if (!status.ok()) return status;
  MarkerFileToModel transform;
  status = LiveTransform(subject, *io.source, config.live.stream_units, &transform);
  if (!status.ok()) return status;
  LiveTracker tracker(skeleton, subject.markers, options, config.live.predict_frames);
  LabelMap label_map(subject.markers, subject.label_prefix);
  const bool bvh = config.live.output_format == "bvh";
  const double rate = io.source->frame_rate();
  std::vector<Eigen::Vector3d> observed(subject.markers.num_markers());
  LiveFrame frame;
  Pose pose;
  int64_t arrival = 0, first_arrival = -1, last_out = 0;
  double sum_sq = 0.0;
  long samples = 0;
  std::string error, bytes;
  while (true) {
    error.clear();
    const LiveFrameSource::Next next = io.source->Read(&frame, &arrival, &error);
    if (next == LiveFrameSource::Next::kEnd || next == LiveFrameSource::Next::kStalled) {
      result->end = next == LiveFrameSource::Next::kEnd ? "closed" : "stalled";
      break;
    }
    if (next == LiveFrameSource::Next::kFatal) return Status::Error(error);
    ++result->frames_in;
    if (first_arrival < 0) first_arrival = arrival;
    if (next == LiveFrameSource::Next::kBadFrame) {
      ++result->bad_frames;
      if (config.live.on_bad_frame == "stop") return Status::Error(error);
      ++result->frames_dropped;
      if (io.warning) io.warning(error + " (skipped)");
      continue;
    }
    const std::vector<int>& columns = label_map.Columns(frame.labels);
    for (int m = 0; m < subject.markers.num_markers(); ++m) {
      const int c = columns[m];
      observed[m] = c >= 0 && frame.positions[c].allFinite() ? transform.Apply(frame.positions[c])
                                                              : Eigen::Vector3d::Constant(std::nan(""));
    }
    LiveTrackReport track;
    status = tracker.Track(observed, &pose, &track);
    if (!status.ok()) return Status::Error("frame " + std::to_string(frame.frame) + ": " + status.message());
    result->unsolved_frames += track.solved ? 0 : 1;
    result->predicted_samples += track.markers_predicted;
    if (track.solved) sum_sq += track.rms_marker_error * track.rms_marker_error * track.markers_observed;
    if (track.solved) samples += track.markers_observed;
    bytes.clear();
    if (bvh && result->frames_out == 0) {
      status = FormatLiveBvhHeader(skeleton, pose, rate, &bytes);
      if (!status.ok()) return status;
    }
    if (bvh) {
      bytes += FormatLiveBvhLine(skeleton, pose);
    } else {
      LivePoseLine line;
      line.frame = frame.frame;
      line.time = frame.time >= 0 ? frame.time : rate > 0 ? frame.frame / rate : 0.0;
      line.markers_used = track.markers_observed;
      line.markers_predicted = track.markers_predicted;
      line.rms = track.rms_marker_error * skeleton.unit().metres_per_unit * 1000.0;
      bytes = FormatLivePoseJson(skeleton, pose, line);
    }
    status = io.write(bytes);
    if (!status.ok()) return Status::Error(status.message() + " (after " + std::to_string(result->frames_out) +
                                           " poses)");
    last_out = SteadyNanoseconds();
    result->latency_ms.push_back((last_out - arrival) * 1e-6);
    ++result->frames_out;
  }
  result->frames_dropped += io.source->dropped();
  result->frames_in += io.source->dropped();
  FillReport(subject, config, first_arrival >= 0 ? (last_out - first_arrival) * 1e-9 : 0.0, sum_sq, samples, result);
  return Status::Ok();
}

}  // namespace mocapsolve
