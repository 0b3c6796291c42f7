#include "apps/corruption_flags.h"

#include "pipeline/corruption_settings.h"

namespace {
// The flags' defaults are the settings' (pipeline/corruption_settings.h): one source.
const mocapsolve::CorruptionSettings kDefault;
}  // namespace

DEFINE_int32(corrupt_seed, kDefault.corrupt_seed, "Seed of every random draw of the damage.");
DEFINE_int32(gaps, kDefault.gaps, "Gaps on random markers.");
DEFINE_int32(gap_min, kDefault.gap_min, "Shortest gap (frames).");
DEFINE_int32(gap_max, kDefault.gap_max, "Longest gap (frames).");
DEFINE_int32(cluster_gaps, kDefault.cluster_gaps, "Occlusions of a marker and its neighbours together.");
DEFINE_double(cluster_radius_mm, kDefault.cluster_radius_mm, "Neighbours within this distance share a cluster gap.");
DEFINE_int32(fly_off_frames, kDefault.fly_off_frames, "Frames before each interior gap in which the marker drifts off.");
DEFINE_double(fly_off_mm, kDefault.fly_off_mm, "How far it drifts (mm) by the gap.");
DEFINE_int32(swaps, kDefault.swaps, "Swaps of a marker with its nearest neighbour.");
DEFINE_int32(swap_length, kDefault.swap_length, "Frames each swap lasts.");
DEFINE_double(swap_radius_mm, kDefault.swap_radius_mm, "Only neighbours this close are swapped.");
DEFINE_int32(noisy_markers, kDefault.noisy_markers, "Markers that get high-frequency noise over an interval.");
DEFINE_int32(noise_length, kDefault.noise_length, "Frames of that interval.");
DEFINE_double(noise_sigma_mm, kDefault.noise_sigma_mm, "Noise per axis (mm).");

namespace mocapsolve {

Status CorruptionOptionsFromFlags(const LengthUnit& unit, CorruptionOptions* options) {
  CorruptionSettings s;
  s.corrupt_seed = FLAGS_corrupt_seed;
  s.gaps = FLAGS_gaps;
  s.gap_min = FLAGS_gap_min;
  s.gap_max = FLAGS_gap_max;
  s.cluster_gaps = FLAGS_cluster_gaps;
  s.cluster_radius_mm = FLAGS_cluster_radius_mm;
  s.fly_off_frames = FLAGS_fly_off_frames;
  s.fly_off_mm = FLAGS_fly_off_mm;
  s.swaps = FLAGS_swaps;
  s.swap_length = FLAGS_swap_length;
  s.swap_radius_mm = FLAGS_swap_radius_mm;
  s.noisy_markers = FLAGS_noisy_markers;
  s.noise_length = FLAGS_noise_length;
  s.noise_sigma_mm = FLAGS_noise_sigma_mm;
  return CorruptionOptionsFromSettings(s, unit, options);
}

}  // namespace mocapsolve
