#include "apps/corruption_flags.h"

DEFINE_int32(corrupt_seed, 1, "Seed of every random draw of the damage.");
DEFINE_int32(gaps, 10, "Gaps on random markers.");
DEFINE_int32(gap_min, 10, "Shortest gap (frames).");
DEFINE_int32(gap_max, 60, "Longest gap (frames).");
DEFINE_int32(cluster_gaps, 2, "Occlusions of a marker and its neighbours together.");
DEFINE_double(cluster_radius_mm, 150.0, "Neighbours within this distance share a cluster gap.");
DEFINE_int32(fly_off_frames, 5, "Frames before each interior gap in which the marker drifts off.");
DEFINE_double(fly_off_mm, 100.0, "How far it drifts (mm) by the gap.");
DEFINE_int32(swaps, 1, "Swaps of a marker with its nearest neighbour.");
DEFINE_int32(swap_length, 30, "Frames each swap lasts.");
DEFINE_double(swap_radius_mm, 200.0, "Only neighbours this close are swapped.");
DEFINE_int32(noisy_markers, 2, "Markers that get high-frequency noise over an interval.");
DEFINE_int32(noise_length, 60, "Frames of that interval.");
DEFINE_double(noise_sigma_mm, 5.0, "Noise per axis (mm).");

namespace mocapsolve {

const char* const kCorruptionFlagNames =
    "corrupt_seed,gaps,gap_min,gap_max,cluster_gaps,cluster_radius_mm,fly_off_frames,fly_off_mm,"
    "swaps,swap_length,swap_radius_mm,noisy_markers,noise_length,noise_sigma_mm";

Status CorruptionOptionsFromFlags(const LengthUnit& unit, CorruptionOptions* options) {
  if (!unit.known()) return Status::Error("unknown length unit: the damage is given in mm");
  if (FLAGS_gap_min < 1 || FLAGS_gap_max < FLAGS_gap_min) {
    return Status::Error("--gap_min/--gap_max: need 1 <= min <= max");
  }
  const double per_mm = 0.001 / unit.metres_per_unit;
  options->seed = static_cast<uint32_t>(FLAGS_corrupt_seed);
  options->gaps = FLAGS_gaps;
  options->gap_min = FLAGS_gap_min;
  options->gap_max = FLAGS_gap_max;
  options->cluster_gaps = FLAGS_cluster_gaps;
  options->cluster_radius = FLAGS_cluster_radius_mm * per_mm;
  options->fly_off_frames = FLAGS_fly_off_frames;
  options->fly_off_distance = FLAGS_fly_off_mm * per_mm;
  options->swaps = FLAGS_swaps;
  options->swap_length = FLAGS_swap_length;
  options->swap_radius = FLAGS_swap_radius_mm * per_mm;
  options->noisy_markers = FLAGS_noisy_markers;
  options->noise_length = FLAGS_noise_length;
  options->noise_sigma = FLAGS_noise_sigma_mm * per_mm;
  return Status::Ok();
}

}  // namespace mocapsolve
