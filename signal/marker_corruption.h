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
//                 a random interval of noise_length frames.
// Lengths are in the trajectories' units. Every draw comes from one std::mt19937 seeded
// with `seed`. The mask (frames x markers) says what was done to each sample:
// 0 clean, 'g' gap, 'f' fly-off, 's' swap, 'n' noise.
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
};

using CorruptionMask = std::vector<std::vector<char>>;

void CorruptMarkers(const CorruptionOptions& options, MarkerTrajectories* markers, CorruptionMask* mask);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_MARKER_CORRUPTION_H_
