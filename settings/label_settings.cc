#include "settings/label_settings.h"

namespace mocapsolve {

const OptionGroup<LabelSettings>& LabelSettingOptions() {
  using S = LabelSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::gate_mm, "gate", "mm",
           "A marker labelled in the previous frame takes a point within this distance of its constant-velocity "
           "prediction.", 0.1, 1e4)
      .Add(&S::reacquire_gate_mm, "reacquire_gate", "mm",
           "A marker missing in the previous frame takes a point within this distance of its model prediction "
           "(the pose solved at the previous frame plus the marker's last offset).", 0.1, 1e4)
      .Add(&S::acquire_gate_mm, "acquire_gate", "mm",
           "Finding the body: a point within this distance of the refined placement's marker matches it.", 0.1, 1e4)
      .Add(&S::cluster_tolerance_mm, "cluster_tolerance", "mm",
           "Finding the body: how far the distances between points may differ from those of a joint's markers.",
           0.1, 1e4)
      .Add(&S::min_confidence, "min_confidence", "",
           "A match less confident than this (0-1: distance to the gate, margin over the nearest competitor) "
           "leaves the point unlabelled.", 0.0, 1.0)
      .Add(&S::accept_fraction, "accept_fraction", "",
           "The body is found when this fraction of the subject's markers is matched within --acquire_gate.",
           0.05, 1.0)
      .Add(&S::acquire_rms_mm, "acquire_rms", "mm",
           "The body is found only when its matches lie at most this far from the refined placement (RMS).",
           0.1, 1e4)
      .Add(&S::lost_fraction, "lost_fraction", "",
           "The body is lost (and looked for again) in a frame that labels fewer than this fraction of the markers "
           "found when it was acquired.", 0.0, 1.0)
      .Add(&S::acquire_frames, "acquire_frames", "frames",
           "Frames with points tried to find the body at the start; none matches: an error.", 1);
  return *group;
}

Status LabellerOptionsFromSettings(const LabelSettings& settings, const LengthUnit& skeleton_unit,
                                   const MarkerSolveOptions& solve, LabellerOptions* options) {
  Status status = LabelSettingOptions().Validate(settings);
  if (!status.ok()) return status;
  if (!skeleton_unit.known()) return Status::Error("the subject's skeleton has no known length unit (gates are in mm)");
  const double units_per_mm = 0.001 / skeleton_unit.metres_per_unit;
  LabellerOptions out;
  out.gate = settings.gate_mm * units_per_mm;
  out.reacquire_gate = settings.reacquire_gate_mm * units_per_mm;
  out.acquisition.gate = settings.acquire_gate_mm * units_per_mm;
  out.acquisition.cluster_tolerance = settings.cluster_tolerance_mm * units_per_mm;
  out.acquisition.accept_fraction = settings.accept_fraction;
  out.acquisition.max_rms = settings.acquire_rms_mm * units_per_mm;
  out.min_confidence = settings.min_confidence;
  out.lost_fraction = settings.lost_fraction;
  out.acquire_frames = settings.acquire_frames;
  out.solve = solve;
  // A marker is missing here because it is not labelled yet, not because it is hidden: a
  // joint held at the subject's mean pose then predicts its markers away from the points
  // they are to be matched to (the demo walk: 98.3 -> 94.7 % of points labelled with it).
  out.solve.hidden_rotation_weight = 0.0;
  *options = out;
  return Status::Ok();
}

}  // namespace mocapsolve
