#include "tasks/label_task.h"

#include <cstdio>

#include "pipeline/take_labelling.h"

namespace mocapsolve {
namespace {

// The console text.
std::string Summary(const LabelResult& result, const TakeLabelling& labelling) {
  const LabellingResult& d = result.details;
  int labelled = 0, swaps = 0, reacquired = 0, refused = 0;
  for (const MarkerLabelStats& s : d.per_marker) {
    labelled += s.labelled, swaps += s.swaps_avoided, reacquired += s.reacquisitions, refused += s.low_confidence;
  }
  const int points = labelling.points, frames = result.markers.num_frames();
  const double fps = result.seconds > 0 ? frames / result.seconds : 0.0;
  char text[512];
  std::snprintf(text, sizeof(text),
                "label: %d frames, %d points: %d labelled (%.2f %%), %d left unlabelled (%d refused for low "
                "confidence); %d swaps avoided, %d re-acquisitions; body found at frame %d, %zu re-acquisitions "
                "of the body, %d frames without it; %.3f s (%.0f frames/s)",
                frames, points, labelled, points > 0 ? 100.0 * labelled / points : 0.0, points - labelled, refused,
                swaps, reacquired, d.first_frame, d.acquisitions.empty() ? 0 : d.acquisitions.size() - 1,
                d.lost_frames, result.seconds, fps);
  return text;
}

}  // namespace

Status RunLabel(const Subject& subject, const MarkerTrajectories& file, const std::string& name,
                const LabelConfig& config, const LabelProgress& progress, LabelResult* result) {
  TakeLabelling labelling;
  Status status = LabelTakeForSubject(subject, file, name, config.label, config.solver, progress, &labelling);
  if (!status.ok()) return status;
  LabelResult out;
  out.report = LabellingReport(subject, labelling);
  out.seconds = labelling.seconds;
  out.details = std::move(labelling.details);
  out.markers = std::move(labelling.markers);
  out.marker_of_sample = std::move(labelling.marker_of_sample);
  out.summary = Summary(out, labelling);
  *result = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
