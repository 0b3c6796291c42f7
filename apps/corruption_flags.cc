#include "apps/corruption_flags.h"

#include "settings/corruption_settings.h"

namespace {
// The flags' defaults are the settings' (settings/corruption_settings.h): one source.
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
DEFINE_int32(swaps_in_gaps, kDefault.swaps_in_gaps, "Swaps that begin inside a gap of one of the two markers (a gap "
             "of --gap_min..--gap_max frames, then --swap_length frames swapped from a frame inside it).");
DEFINE_int32(jitter_markers, kDefault.jitter_markers, "Markers displaced by --jitter_mm x U(0.5, 1.5) in a random "
             "direction every frame of an interval: errors below a fixed outlier distance.");
DEFINE_int32(jitter_length, kDefault.jitter_length, "Frames of each jitter interval.");
DEFINE_double(jitter_mm, kDefault.jitter_mm, "Typical jitter displacement (mm): 20 gives 10-30 mm.");
DEFINE_int32(ghosts, kDefault.ghosts, "Runs in which a marker's label sits on a ghost reflection near it.");
DEFINE_int32(ghost_length, kDefault.ghost_length, "Frames of each ghost run.");
DEFINE_double(ghost_mm, kDefault.ghost_mm, "Distance of the ghost from the marker (mm), constant over its run.");
DEFINE_int32(unlabels, kDefault.unlabels, "Runs in which a marker's samples lose their label: they move to a new "
             "unlabelled track (*1, *2, ...), as points a labeller could not name.");
DEFINE_int32(unlabel_length, kDefault.unlabel_length, "Frames of each unlabelled run.");

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
  s.swaps_in_gaps = FLAGS_swaps_in_gaps;
  s.jitter_markers = FLAGS_jitter_markers;
  s.jitter_length = FLAGS_jitter_length;
  s.jitter_mm = FLAGS_jitter_mm;
  s.ghosts = FLAGS_ghosts;
  s.ghost_length = FLAGS_ghost_length;
  s.ghost_mm = FLAGS_ghost_mm;
  s.unlabels = FLAGS_unlabels;
  s.unlabel_length = FLAGS_unlabel_length;
  return CorruptionOptionsFromSettings(s, unit, options);
}

}  // namespace mocapsolve
