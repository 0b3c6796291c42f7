// Per-marker solve weights learned on a calibration take: each marker's tolerance.
//
// Soft tissue moves some markers on their bone more than others (upper arm, thigh,
// belly). Solving a calibration take frame by frame with every marker (SolveSequence,
// the subject's own offsets), marker m's residual r_m(f) = |x^_m(f) - y_m(f)| over the
// frames where it was observed has the spread
//   sigma_m = sqrt(mean_f r_m(f)^2),
// and with sigma_ref the median of sigma_m over the markers, its weight is
//   w_m = clamp((sigma_ref / sigma_m)^2, min_weight, 1)
// (1/sigma^2 relative to the set's typical marker; a marker tighter than the median is
// not trusted more than 1, so a few rigid markers do not take the pose over). The solvers
// scale m's residual rows by sqrt(w_m) (MarkerSpec::solve_weight), so a loose marker pulls
// the pose less and its neighbours decide it. A loose marker also drags the pose, and so
// its neighbours' residuals, in the first solve; so the take is solved `rounds` times, each
// with the previous round's weights (iteratively reweighted), and the last round's spreads
// give the weights. Lengths in skeleton units.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_WEIGHTS_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_WEIGHTS_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

struct MarkerWeightOptions {
  double min_weight = 0.1;  // The lowest weight a marker gets, in (0, 1].
  int min_samples = 10;     // A marker observed in fewer frames keeps weight 1.
  int rounds = 3;           // Solve, weigh, solve again with the weights (>= 1).
};

struct LearnedMarkerWeights {
  std::vector<double> sigma;   // Per marker, skeleton units (0 where not measured).
  std::vector<int> samples;    // Frames each marker was observed in.
  std::vector<double> weight;  // Per marker, in [min_weight, 1].
  double sigma_ref = 0.0;      // Median of the measured sigmas.
};

// observed[f][m] in skeleton units (NaN = missing). The solve uses `options` as given
// (its own weights included); the result is the markers' new weights, not applied.
Status LearnMarkerWeights(const Skeleton& skeleton, const MarkerSet& markers,
                          const std::vector<std::vector<Eigen::Vector3d>>& observed,
                          const MarkerSolveOptions& options, const MarkerWeightOptions& weight_options,
                          LearnedMarkerWeights* learned);

// The marker set with the learned weights as each marker's solve_weight.
Status ApplyMarkerWeights(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<double>& weights,
                          MarkerSet* weighted);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_WEIGHTS_H_
