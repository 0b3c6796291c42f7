// Per-marker robust model of the residual against the reference (issue 16 item 2): a
// sample is judged by how far it departs from its own marker's typical residual, not from
// zero, so a marker whose calibrated offset is a few cm off (a constant residual) or that
// sits on loose tissue (a wide one) is not cut away, while 1-4 cm jumps on a marker that is
// normally within millimetres are found.
//
// For marker m, riding mainly on joint j (its largest attachment weight), the residual of
// sample x_fm against its reconstruction X^_fm = LBS(Y^_f, Z) is taken in the joint's frame,
//   d_fm = R_j(Y^_f)^T (x_fm - X^_fm)          (skeleton units),
// so an error of the marker's offset is one constant vector. Over the take's valid samples:
//   c_m  = component-wise median of d_fm        (the marker's typical residual),
//   e_fm = |d_fm - c_m|                          (deviation from it),
//   s_m  = 1.4826 * median_f |e_fm - median_f e_fm|   (MAD, a robust standard deviation),
//   t_m  = clamp(median_f e_fm + k s_m, min_distance, max_distance)   (the take-wide gate).
// The typical prediction T_fm = X^_fm + R_j(Y^_f) c_m and gate t_m serve swap detection,
// which must see a displacement however long it lasts.
// Outliers are judged against a model of soft-tissue motion: on a real take the residual
// drifts by centimetres with the pose (a shoulder marker during punches), slowly, while a
// broken sample jumps. So the soft-tissue residual is the running component-wise median
// of d over `window` frames (valid samples only), S_fm, the prediction is
// P_fm = X^_fm + R_j(Y^_f) S_fm, and the outlier gate u_m is the same robust statistic as
// t_m taken over e'_fm = |d_fm - S_fm|; a sample is an outlier when |x_fm - P_fm| > u_m.
// With u_m at least max_distance, this is chapter 3's fixed rule measured from the
// soft-tissue prediction instead of X^: it catches large errors only.
// Small errors (1-4 cm jumps, jitter) are told from soft tissue by being discontinuous:
// the residual steps, v_fm = d_fm - d_(f-1)m between consecutive valid samples, have a
// robust gate w_m (the same statistic over |v_fm|, at least min_distance, no cap); a step
// past w_m into a displacement and the next step back out (|v_a + v_b|, or the residual
// after it against the one before v_a, within max(w_m, |v_a| / 2): the reference leans
// toward a displaced marker, so the way out can be smaller than the way in; at most
// max_jump_frames later, the mean residual in between at
// least |v_a| / 2 from the one before along v_a) mark frames a..b-1 as jumped; an unmatched step marks its own
// frame; of those, only samples displaced more than min_distance from the soft-tissue
// residual (|d_fm - S_fm|) count as jumped (noise of a few mm steps by about a cm from frame
// to frame, and a refill would be worse than it). A sharp, short pair is the exception:
// when both steps are at least 5 times the marker's own step statistic before the floor
// (median + k MAD of |v_fm|, so a marker that is normally within millimetres qualifies and
// a loose one does not) and it lasts less than window / 2 frames, a sample in between
// counts as jumped also when displaced from the residual before the step by at least half
// the step along it (the reference leans toward a displaced marker and takes it under
// the floor). A calm plateau is found even with steps under the floor: a step in and a
// step out of at least 3 times the marker's own step statistic and half the floor, the
// step before the one in, every step inside and the one after the one out under 0.3 of
// the step in, 2 to window / 2 samples long (a marker displaced and held still; noise
// steps at every frame, soft tissue does not step). It counts only where the captured
// samples themselves jump at both ends, |(x_a - x_(a-1)) - (x_(a-1) - x_(a-2))| at least
// half the step (and likewise at the step out): when the reference turns a joint toward
// a displaced marker, its other markers get residual plateaus while their samples move
// smoothly. Under white noise (1 mm per axis makes the marker's own step statistic ~7 mm)
// single steps cannot see a 1-1.5 cm jump, so plateaus are also found on windowed steps,
// D_f = mean(d_f..d_(f+k-1)) - mean(d_(f-k)..d_(f-1)) with k = 4, whose noise falls as
// 1/sqrt(k): a step in at a local peak of |D| of at least 2 times its own statistic
// (median + k MAD of |D|) and half the floor, a step out k to window / 2 samples later, D
// calm (under 0.3 of the step in) a window before, between the steps and a window after,
// back as above; each end is put on the sharpest single step within a frame of the peak,
// and the same raw-sample check applies. A sample is an outlier when jumped or
// |x_fm - P_fm| > u_m.
// A jump the reference absorbs: on a bone one marker pins (a head, a thumb, a wrist) the
// robust reference turns the joint to follow the jumped marker, so d steps by a fraction
// of the jump. Seen from the joint's parent instead, with the joint's own rotation
// replaced by its running median Q~_j(f) (component-wise over `window` frames of
// log(Q_j), Q_j the reference's local rotation), the marker
//   p_fm = Q~_j(f)^T Q_j(f) R_j(Y^_f)^T (x_fm - o_j(Y^_f))      (o_j: the joint's origin)
// steps by the whole jump, while real motion of the joint (smooth) stays in Q~ or moves
// p slowly. Steps of p are paired exactly as those of d (their own gate, soft-tissue
// median, floor, sharp-pair exception and calm plateaus), but a step of p counts only
// when d steps with it, by at least 0.2 of its length along it (turned into the joint's
// frame): a sudden turn of an ancestor that the joint's own rotation undoes moves p, not
// d, and is no jump of the marker. Samples so found are `absorbed`, and outliers as the jumped ones. The check trusts the
// reference's parent frames: where a swap was undone the reference had followed the
// swapped labels, so the repair clears `absorbed` on the relabelled samples.
// The fixed model of chapter 3 is P = T = X^, u_m = t_m = fixed_distance and no jumps
// (`robust` false).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_MARKER_RESIDUAL_MODEL_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_MARKER_RESIDUAL_MODEL_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

struct ResidualModelOptions {
  bool robust = true;
  double mads = 6.0;             // k: robust standard deviations past the median deviation.
  double min_distance = 0.0;     // Skeleton units; the gate never goes below it.
  double max_distance = 0.0;     // Skeleton units; t_m at most, u_m at least this (<= 0: none).
  double fixed_distance = 0.0;   // Skeleton units; the gate when !robust.
  int window = 61;               // Frames of the soft-tissue running median (odd; <= 1: none).
  int max_jump_frames = 120;     // Longest displacement the step pairing bounds.
};

struct MarkerResidualModel {
  // predicted[f][m] = P_fm, typical_predicted[f][m] = T_fm (skeleton units; every frame,
  // also where x is missing).
  std::vector<std::vector<Eigen::Vector3d>> predicted, typical_predicted;
  std::vector<Eigen::Vector3d> typical;  // c_m, in the marker's joint frame.
  std::vector<double> median_deviation;  // median_f e'_fm.
  std::vector<double> scale;             // Robust standard deviation of e'_fm.
  std::vector<double> gate;              // u_m.
  std::vector<double> typical_gate;      // t_m.
  std::vector<double> step_gate;         // w_m.
  std::vector<std::vector<char>> jumped;  // [f][m], 1 = inside a jump (robust model only).
  std::vector<std::vector<char>> absorbed;  // [f][m], 1 = inside a jump found from the parent.

  bool Outlying(int f, int m, const Eigen::Vector3d& sample) const {
    return jumped[f][m] || absorbed[f][m] || (sample - predicted[f][m]).norm() > gate[m];
  }
};

// reconstructed[f][m] = X^_fm; `reference` is Y^ (for R_j); x the observed samples.
MarkerResidualModel FitMarkerResidualModel(const Skeleton& skeleton, const MarkerSet& markers,
                                           const Motion& reference,
                                           const std::vector<std::vector<Eigen::Vector3d>>& reconstructed,
                                           const MarkerTrajectories& x, const ResidualModelOptions& options);
// The same with X^ as trajectories (X^_fm = reconstructed.position(f, m)).
MarkerResidualModel FitMarkerResidualModel(const Skeleton& skeleton, const MarkerSet& markers,
                                           const Motion& reference, const MarkerTrajectories& reconstructed,
                                           const MarkerTrajectories& x, const ResidualModelOptions& options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_MARKER_RESIDUAL_MODEL_H_
