#include "pipeline/corruption_settings.h"

#include <cstdint>

namespace mocapsolve {

Status CorruptionOptionsFromSettings(const CorruptionSettings& settings, const LengthUnit& unit,
                                     CorruptionOptions* options) {
  if (!unit.known()) return Status::Error("unknown length unit: the damage is given in mm");
  if (settings.gap_min < 1 || settings.gap_max < settings.gap_min) {
    return Status::Error("--gap_min/--gap_max: need 1 <= min <= max");
  }
  const double per_mm = 0.001 / unit.metres_per_unit;
  options->seed = static_cast<uint32_t>(settings.corrupt_seed);
  options->gaps = settings.gaps;
  options->gap_min = settings.gap_min;
  options->gap_max = settings.gap_max;
  options->cluster_gaps = settings.cluster_gaps;
  options->cluster_radius = settings.cluster_radius_mm * per_mm;
  options->fly_off_frames = settings.fly_off_frames;
  options->fly_off_distance = settings.fly_off_mm * per_mm;
  options->swaps = settings.swaps;
  options->swap_length = settings.swap_length;
  options->swap_radius = settings.swap_radius_mm * per_mm;
  options->noisy_markers = settings.noisy_markers;
  options->noise_length = settings.noise_length;
  options->noise_sigma = settings.noise_sigma_mm * per_mm;
  return Status::Ok();
}

}  // namespace mocapsolve
