// Labelling fixtures and their score: a labelled take turned into a raw point cloud (labels
// stripped, points shuffled every frame, ghosts added, samples dropped, noise), with the
// truth kept, and a labelling scored against that truth. Used by the tests and the
// benchmarks of marker labelling (marker_labeller.h); lengths in the take's own unit.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_LABEL_LABEL_FIXTURE_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_LABEL_LABEL_FIXTURE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "kinematics/marker_trajectories.h"

namespace mocapsolve {

struct ScrambleOptions {
  int ghosts = 0;             // Ghost points added per frame, uniform in the frame's point
                              // bounds grown by ghost_margin on every side.
  double ghost_margin = 0.0;  // Take units.
  double dropout = 0.0;       // Probability that a sample is dropped.
  double noise = 0.0;         // Standard deviation per axis (take units).
  std::uint32_t seed = 1;
};

struct ScrambledTake {
  // Columns "*1".."*K" (K the most points of a frame), each frame's points in random
  // columns; the take's rate, unit and first frame.
  MarkerTrajectories points;
  // truth[f][c]: the label (subject prefix stripped) of the sample in column c at frame f,
  // "" for a ghost, an empty column, or a column the take itself left unlabelled ("*52").
  std::vector<std::vector<std::string>> truth;
};

ScrambledTake ScrambleLabels(const MarkerTrajectories& labelled, const ScrambleOptions& options);

struct LabelScore {
  int truth_samples = 0;    // Samples whose truth is a label of the scored set.
  int correct = 0;          // ... given that label.
  int wrong = 0;            // Samples given a label that is not their truth (ghosts included).
  int unlabelled = 0;       // Truth samples left without a label.
  int longest_wrong_run = 0;  // Frames, the longest run of one label given to wrong points.
  double accuracy() const { return truth_samples > 0 ? static_cast<double>(correct) / truth_samples : 0.0; }
};

// labels[f][c]: the label given to column c at frame f ("" = none); `scored`: the labels
// that count (a subject's markers: truth labels outside it count as "").
LabelScore ScoreLabels(const std::vector<std::vector<std::string>>& truth,
                       const std::vector<std::vector<std::string>>& labels, const std::vector<std::string>& scored);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_LABEL_LABEL_FIXTURE_H_
