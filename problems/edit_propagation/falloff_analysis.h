// Falloff analysis: the figures the distance command reports and the tests check, for a
// falloff computed by falloff.h on a clip's pose vectors (pose_features.h).
//
// Period: s(l) = mean_i |p_{i+l} - p_i| over the clip. The period is the first lag
// l >= min_lag where s has a local minimum (over l +- 3) after having risen, with
// s(l) < 0.5 * max_{l' < l} s(l'); 0 when there is none (a non-periodic clip). Lags are
// searched up to 2/3 of the clip so at least a third of it overlaps.
// Phases of frame i: for each other cycle k != 0 with i + k T inside the clip, the "same
// phase" frame is the pose nearest p_i within T/4 of i + k T; the "opposite phase" frames
// lie halfway between consecutive same-phase frames (frame i included) and T/2 before the
// first and after the last, where inside the clip.
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_FALLOFF_ANALYSIS_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_FALLOFF_ANALYSIS_H_

#include <vector>

#include <Eigen/Core>

namespace mocapsolve {

// Frames; 0 if none found. features: #frames x D.
int DetectPosePeriod(const Eigen::MatrixXd& features, int min_lag = 10);

struct PhaseFrames {
  std::vector<int> same;      // Ascending frame indices.
  std::vector<int> opposite;  // Ascending frame indices.
};
PhaseFrames FindPhaseFrames(const Eigen::MatrixXd& features, int frame, int period);

// v[i-1] - 2 v[i] + v[i+1]; NaN at the ends.
double SecondDifference(const Eigen::VectorXd& values, int frame);

// Scale-free corner measure at `frame`: |v[i-1] - 2 v[i] + v[i+1]| divided by the mean
// of the neighbouring slopes |v[i+2] - v[i+1]| and |v[i-1] - v[i-2]|. About 2/3 for a
// smooth (parabolic) peak, 2 for a corner like |x|; NaN within 2 frames of the ends or
// when those slopes are 0.
double KinkRatio(const Eigen::VectorXd& values, int frame);

// The first frame after (direction +1) or before (-1) `frame` whose weight is below
// `threshold`; -1 if the weight never drops below it on that side.
int FalloffEnd(const Eigen::VectorXd& weight, int frame, int direction, double threshold);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_FALLOFF_ANALYSIS_H_
