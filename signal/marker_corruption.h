// Synthetic corruption of clean marker trajectories, for evaluating repair (issue 4):
// the damage real captures show (thesis 1.4.1, 3.3.4), with a ground-truth mask.
//
//   gaps          `gaps` runs of missing samples on random markers, lengths uniform in
//                 [gap_min, gap_max] frames;
//   cluster gaps  `cluster_gaps` occlusions: a random marker and every marker within
//                 cluster_radius of it (at the gap's first frame) go missing together;
//   fly-off       the fly_off_frames valid samples just before each interior gap drift
//                 away, linearly up to fly_off_distance, in a random direction;
//   swaps         `swaps` times a marker and its nearest neighbour (within swap_radius)
//                 exchange positions for swap_length frames;
//   noise         `noisy_markers` markers get Gaussian noise of noise_sigma per axis over
//                 a random interval of noise_length frames;
// and the damage real cleanup meets that stays near the marker (issue 16; off by default):
//   swaps in gaps `swaps_in_gaps` times a marker goes missing (a gap of gap_min..gap_max
//                 frames) and, from a frame inside that gap, it and its nearest neighbour
//                 exchange positions for swap_length frames: the swap begins unseen;
//   jitter        `jitter_markers` markers are displaced, every frame of a random
//                 interval of jitter_length frames, by jitter_distance x U(0.5, 1.5) in a
//                 random direction (1-3 cm for 2 cm): errors under a fixed outlier distance;
//   ghosts        `ghosts` times a marker's label sits on a ghost reflection for
//                 ghost_length frames: the sample is offset by ghost_distance in one random
//                 direction, constant over the run.
//   unlabelled    `unlabels` times a marker's samples over unlabel_length frames lose
//                 their label: they leave the marker (missing there) for a new unlabelled
//                 track ("*1", "*2", ... in `unlabelled`, one per event), as a capture's
//                 labeller leaves points it cannot name; relabelling should bring them back.
// Lengths are in the trajectories' units. Every draw comes from one std::mt19937 seeded
// with `seed`, the kinds drawn in the order above, so adding a later kind leaves the
// earlier damage of a seed as it was. The mask (frames x markers) says what was done to
// each sample: 0 clean, or the kind's letter in kDamageKinds.
#ifndef MOCAPSOLVE_SIGNAL_MARKER_CORRUPTION_H_
#define MOCAPSOLVE_SIGNAL_MARKER_CORRUPTION_H_

#include <cstdint>
#include <vector>

#include "kinematics/marker_trajectories.h"

namespace mocapsolve {

struct CorruptionOptions {
  uint32_t seed = 1;
  int gaps = 10;
  int gap_min = 10, gap_max = 60;
  int cluster_gaps = 2;
  double cluster_radius = 0.0;
  int fly_off_frames = 5;
  double fly_off_distance = 0.0;
  int swaps = 1;
  int swap_length = 30;
  double swap_radius = 0.0;
  int noisy_markers = 2;
  int noise_length = 60;
  double noise_sigma = 0.0;
  int swaps_in_gaps = 0;
  int jitter_markers = 0;
  int jitter_length = 60;
  double jitter_distance = 0.0;
  int ghosts = 0;
  int ghost_length = 20;
  double ghost_distance = 0.0;
  int unlabels = 0;
  int unlabel_length = 30;
};

// The unlabelled tracks the unlabelled damage made: tracks.label(k) = "*<k+1>", holding
// marker source[k]'s samples (exactly as they were) over its interval, missing elsewhere.
struct UnlabelledDamage {
  MarkerTrajectories tracks;
  std::vector<int> source;
};

// The mask's letters and the kinds' names, in the same order: gap, fly-off, swap, noise,
// jitter, ghost, unlabelled (a swap that begins in a gap is 'g' there and 's' after).
inline constexpr int kNumDamageKinds = 7;
inline constexpr char kDamageKinds[kNumDamageKinds + 1] = "gfsnjhu";
inline constexpr const char* kDamageKindNames[kNumDamageKinds] = {"gap", "fly_off", "swap", "noise", "jitter",
                                                                   "ghost", "unlabelled"};
// The index of a mask letter in kDamageKinds, -1 for 0 or an unknown letter.
int DamageKindIndex(char letter);

using CorruptionMask = std::vector<std::vector<char>>;

// `unlabelled` (optional) receives the unlabelled damage's tracks (without it the samples
// are only removed); it has the markers' frame count, unit and frame rate.
void CorruptMarkers(const CorruptionOptions& options, MarkerTrajectories* markers, CorruptionMask* mask,
                    UnlabelledDamage* unlabelled = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_MARKER_CORRUPTION_H_
