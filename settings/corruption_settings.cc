#include "settings/corruption_settings.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

namespace mocapsolve {

Status CorruptionOptionsFromSettings(const CorruptionSettings& settings, const LengthUnit& unit,
                                     CorruptionOptions* options) {
  if (!unit.known()) return Status::Error("unknown length unit: the damage is given in mm");
  if (settings.gap_min < 1 || settings.gap_max < settings.gap_min) {
    return Status::Error("--gap_min/--gap_max: need 1 <= min <= max");
  }
  const std::pair<const char*, int> counts[] = {
      {"gaps", settings.gaps}, {"cluster_gaps", settings.cluster_gaps}, {"fly_off_frames", settings.fly_off_frames},
      {"swaps", settings.swaps}, {"swap_length", settings.swap_length}, {"noisy_markers", settings.noisy_markers},
      {"noise_length", settings.noise_length}, {"swaps_in_gaps", settings.swaps_in_gaps},
      {"jitter_markers", settings.jitter_markers}, {"jitter_length", settings.jitter_length},
      {"ghosts", settings.ghosts}, {"ghost_length", settings.ghost_length}, {"unlabels", settings.unlabels},
      {"unlabel_length", settings.unlabel_length}};
  for (const auto& [name, value] : counts) {
    if (value < 0) return Status::Error(std::string("--") + name + ": expected >= 0, got " + std::to_string(value));
  }
  const std::pair<const char*, double> distances[] = {
      {"cluster_radius_mm", settings.cluster_radius_mm}, {"fly_off_mm", settings.fly_off_mm},
      {"swap_radius_mm", settings.swap_radius_mm}, {"noise_sigma_mm", settings.noise_sigma_mm},
      {"jitter_mm", settings.jitter_mm}, {"ghost_mm", settings.ghost_mm}};
  for (const auto& [name, value] : distances) {
    if (!std::isfinite(value) || value < 0.0) {
      return Status::Error(std::string("--") + name + ": expected a finite distance >= 0 (mm)");
    }
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
  options->swaps_in_gaps = settings.swaps_in_gaps;
  options->jitter_markers = settings.jitter_markers;
  options->jitter_length = settings.jitter_length;
  options->jitter_distance = settings.jitter_mm * per_mm;
  options->ghosts = settings.ghosts;
  options->ghost_length = settings.ghost_length;
  options->ghost_distance = settings.ghost_mm * per_mm;
  options->unlabels = settings.unlabels;
  options->unlabel_length = settings.unlabel_length;
  return Status::Ok();
}

}  // namespace mocapsolve
