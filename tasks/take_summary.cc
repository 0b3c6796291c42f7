#include "tasks/take_summary.h"

#include "tasks/console_text.h"

namespace mocapsolve {

std::string TakeSummary(const TakeInputs& inputs, const TakeResult& result) {
  std::string text;
  const int frames = result.frames;
  AppendF(&text, "pipeline %s: %d frames in %.2f s (%.0f frames/s)\n", inputs.name.c_str(), frames, result.seconds,
          result.seconds > 0 ? frames / result.seconds : 0.0);
  for (const StageTime& t : result.timings) AppendF(&text, "  %-32s %8.3f s\n", t.stage.c_str(), t.seconds);
  if (result.labelled_points > 0) {
    AppendF(&text, "  labelled first: %d of %d points given the subject's labels (%.2f %%)\n", result.labelled_samples,
            result.labelled_points, 100.0 * result.labelled_samples / result.labelled_points);
  }
  AppendF(&text, "  marker RMS naive %.2f mm, repaired %.2f mm; %d of %d samples repaired (%.2f %%)\n",
          result.figures.naive_rms_mm, result.figures.repaired_rms_mm, result.repaired_samples, result.samples,
          100.0 * result.figures.repaired_share);
  for (const CharacterOutput& c : result.characters) {
    const RetargetClipResult& r = c.result.clip;
    AppendF(&text, "  %s: vertex error %.4f of height, foot skating %.2f -> %.2f cm/s\n", c.name.c_str(),
            r.mean_position_error, c.result.source_plant_skating_cm_s, c.result.result_plant_skating_cm_s);
  }
  return text;
}

std::string TakeGateFailures(const TakeResult& result) {
  std::string failures;
  for (const std::string& f : result.verdict.failures) failures += (failures.empty() ? "" : "; ") + f;
  if (!result.gate_advice.empty()) failures += "\n  " + result.gate_advice;
  return failures;
}

}  // namespace mocapsolve
