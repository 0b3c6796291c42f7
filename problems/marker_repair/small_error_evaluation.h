// Small-error detection on a take (issue 16 item 2): how many of the samples displaced
// by a known recipe of 1-4 cm errors the repair flags (recall), and how many of the
// samples it flags were damaged (precision).
//
// The recipe, per seed (one std::mt19937(seed), draws in this order, the order the
// real-data test always used, so its figures carry over):
//   `jumps` jumps: a random marker, a length uniform in 1..jump_max_frames, a first frame
//                  uniform in [5, nf - length - 5], and, when the marker is free of
//                  earlier damage within 5 frames, a size uniform in [jump_min, jump_max]
//                  along a random direction, added to every frame of the run;
//   `jitter_runs` runs of jitter_frames frames drawn the same way (no length draw), each
//                  frame displaced by a Gaussian vector of jitter_distance RMS length
//                  (jitter_distance / sqrt(3) per axis); a displacement under min_error
//                  is left out (not an error to find).
// Missing samples stay missing. `white_noise` (per-axis standard deviation, 0: none)
// is added to every observed sample before the damage, from a second generator seeded
// with the seed, so the damage draws do not depend on it: on a noise-free synthetic take
// it makes the marker's own step statistic that of a real capture.
//
// Scoring: a sample is flagged when it lies inside a `detected` interval of the repair
// report other than "missing" (gaps are not detections). Per seed the repair also runs on
// the undamaged take (noise included): the samples it flags there are the take's own
// glitches, neither true nor false for the added damage. Precision is reported raw
//   true / flagged,
// and without them: (true - own true) / (flagged - own flagged). Recall is raw.
// All distances in the skeleton's units.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_SMALL_ERROR_EVALUATION_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_SMALL_ERROR_EVALUATION_H_

#include <cstdint>
#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_repair/marker_repair.h"

namespace mocapsolve {

struct SmallErrorRecipe {
  uint32_t seed = 1;
  int jumps = 12;
  int jump_max_frames = 20;
  double jump_min = 0.0, jump_max = 0.0;
  int jitter_runs = 3;
  int jitter_frames = 10;
  double jitter_distance = 0.0;
  double min_error = 0.0;
  double white_noise = 0.0;
};

// The recipe in a skeleton of `metres_per_unit`: jumps of 1-4 cm, jitter of 2 cm,
// errors under 1 cm left out; white noise `white_noise_mm` (mm per axis).
SmallErrorRecipe DefaultSmallErrorRecipe(double metres_per_unit, double white_noise_mm = 0.0);

using SampleFlags = std::vector<std::vector<char>>;  // [frame][marker], 1 = set.

// Adds the recipe's white noise to `observed` ([frame][marker], NaN = missing).
void AddWhiteNoise(const SmallErrorRecipe& recipe, std::vector<std::vector<Eigen::Vector3d>>* observed);
// Adds the recipe's jumps and jitter to `observed`; damaged[f][m] = 1 where a sample moved.
void AddSmallErrors(const SmallErrorRecipe& recipe, std::vector<std::vector<Eigen::Vector3d>>* observed,
                    SampleFlags* damaged);

// The samples inside the report's detected intervals other than "missing".
SampleFlags FlaggedSamples(const RepairReport& report, int num_frames, int num_markers);

// Sample counts of one seed or of all, and the figures made from them.
struct SmallErrorCounts {
  long damaged = 0;        // Samples the recipe moved.
  long flagged = 0;        // Samples the repair flagged on the damaged take.
  long true_positive = 0;  // Both.
  long own = 0;            // Flagged on the damaged take and on the undamaged one...
  long own_damaged = 0;    // ...of which damaged.

  double Recall() const { return damaged > 0 ? double(true_positive) / damaged : 1.0; }
  double Precision() const { return flagged > 0 ? double(true_positive) / flagged : 1.0; }
  double PrecisionWithoutOwn() const {
    return flagged > own ? double(true_positive - own_damaged) / (flagged - own) : 1.0;
  }
  SmallErrorCounts& operator+=(const SmallErrorCounts& other);
};

struct SmallErrorSeedScore : SmallErrorCounts {
  uint32_t seed = 0;
  // [frame][marker]: damaged, flagged, and flagged on the undamaged take (own).
  SampleFlags damaged_samples, flagged_samples, own_samples;
};

struct SmallErrorScore : SmallErrorCounts {  // Summed over the seeds.
  std::vector<SmallErrorSeedScore> seeds;
};

// Runs the recipe with seeds first_seed .. first_seed + num_seeds - 1 on `clean`
// ([frame][marker], skeleton units) and scores RepairMarkers(options).
Status EvaluateSmallErrors(const Skeleton& skeleton, const MarkerSet& markers,
                           const std::vector<std::vector<Eigen::Vector3d>>& clean, const RepairOptions& options,
                           const SmallErrorRecipe& recipe, int num_seeds, SmallErrorScore* score);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_SMALL_ERROR_EVALUATION_H_
