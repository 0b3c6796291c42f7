#include "settings/corruption_settings.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

namespace mocapsolve {

const OptionGroup<CorruptionSettings>& CorruptionSettingOptions() {
  using S = CorruptionSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::seed, "seed", "",
           "Seed of every random draw of the damage.")
      .Add(&S::gaps, "gaps", "gaps",
           "Gaps on random markers.")
      .Add(&S::gap_min, "gap_min", "frames",
           "Shortest gap (frames).")
      .Add(&S::gap_max, "gap_max", "frames",
           "Longest gap (frames).")
      .Add(&S::cluster_gaps, "cluster_gaps", "gaps",
           "Occlusions of a marker and its neighbours together.")
      .Add(&S::cluster_radius_mm, "cluster_radius_mm", "mm",
           "Neighbours within this distance share a cluster gap.")
      .Add(&S::fly_off_frames, "fly_off_frames", "frames",
           "Frames before each interior gap in which the marker drifts off.")
      .Add(&S::fly_off_mm, "fly_off_mm", "mm",
           "How far it drifts (mm) by the gap.")
      .Add(&S::swaps, "swaps", "swaps",
           "Swaps of a marker with its nearest neighbour.")
      .Add(&S::swap_length, "swap_length", "frames",
           "Frames each swap lasts.")
      .Add(&S::swap_radius_mm, "swap_radius_mm", "mm",
           "Only neighbours this close are swapped.")
      .Add(&S::noisy_markers, "noisy_markers", "markers",
           "Markers that get high-frequency noise over an interval.")
      .Add(&S::noise_length, "noise_length", "frames",
           "Frames of that interval.")
      .Add(&S::noise_sigma_mm, "noise_sigma_mm", "mm",
           "Noise per axis (mm).")
      .Add(&S::swaps_in_gaps, "swaps_in_gaps", "swaps",
           "Swaps that begin inside a gap of one of the two markers (a gap "
           "of --gap_min..--gap_max frames, then --swap_length frames swapped from a frame inside it).")
      .Add(&S::jitter_markers, "jitter_markers", "markers",
           "Markers displaced by --jitter_mm x U(0.5, 1.5) in a random "
           "direction every frame of an interval: errors below a fixed outlier distance.")
      .Add(&S::jitter_length, "jitter_length", "frames",
           "Frames of each jitter interval.")
      .Add(&S::jitter_mm, "jitter_mm", "mm",
           "Typical jitter displacement (mm): 20 gives 10-30 mm.")
      .Add(&S::ghosts, "ghosts", "ghosts",
           "Runs in which a marker's label sits on a ghost reflection near it.")
      .Add(&S::ghost_length, "ghost_length", "frames",
           "Frames of each ghost run.")
      .Add(&S::ghost_mm, "ghost_mm", "mm",
           "Distance of the ghost from the marker (mm), constant over its run.")
      .Add(&S::unlabels, "unlabels", "markers",
           "Runs in which a marker's samples lose their label: they move to a new "
           "unlabelled track (*1, *2, ...), as points a labeller could not name.")
      .Add(&S::unlabel_length, "unlabel_length", "frames",
           "Frames of each unlabelled run.");
  return *group;
}

Status CorruptionOptionsFromSettings(const CorruptionSettings& settings, const LengthUnit& unit,
                                     CorruptionOptions* options) {
  Status checked = CorruptionSettingOptions().Validate(settings);
  if (!checked.ok()) return checked;
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
  options->seed = static_cast<uint32_t>(settings.seed);
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
