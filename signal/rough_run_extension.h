// Cutting a rough run whole: the samples beside a detected rough run that are as rough as
// it (issue 16, the noise kind).
//
// A run of white noise on a marker (each sample displaced independently) is detected only
// where a sample's displacement passes the marker's gate: the samples with small draws,
// and those at the run's ends, stay, and keep their noise. Roughness here is the
// |second difference| of the residual r = X - R (X the samples, R the marker's reference
// path, which carries the body's own acceleration so that r does not):
//   s(f) = |r(f + 1) - 2 r(f) + r(f - 1)|,
// defined where X and R are valid at f - 1, f, f + 1. With noise n of sigma per axis on a
// run [p, q] and none elsewhere, s is ~sqrt(18) sigma inside, ~sqrt(15) sigma at p and q,
// and ~sqrt(3) sigma at p - 1 and q + 1 (the first clean samples, which see one noisy
// neighbour), then the marker's own level. So the contiguous stretch of s above a
// threshold around the run is [p - 1, q + 1] when it sees the run's ends, and the noisy
// samples are its interior: ExtendRoughRun walks from the detected gap outwards while s
// stays above `threshold` (through samples already missing from *x but present in
// `samples`; a sample missing from `samples` ends the walk) and cuts the interior of the
// stretch from *x. A stretch that ends at the take's first or last valid sample keeps
// that sample (it has no second difference to judge it by). Lengths in the markers' units.
#ifndef MOCAPSOLVE_SIGNAL_ROUGH_RUN_EXTENSION_H_
#define MOCAPSOLVE_SIGNAL_ROUGH_RUN_EXTENSION_H_

#include "kinematics/marker_trajectories.h"
#include "signal/gap_fill.h"

namespace mocapsolve {

// s(f) above; -1 where it is not defined (a missing sample or f at the take's ends). With
// reference null, the samples' own second difference |X(f + 1) - 2 X(f) + X(f - 1)|.
double SecondDifference(const MarkerTrajectories& samples, const MarkerTrajectories* reference, int marker,
                        int frame);

// Median SecondDifference of `marker` over frames [first, last] where it is defined; -1 if
// none.
double MedianSecondDifference(const MarkerTrajectories& samples, const MarkerTrajectories* reference, int marker,
                              int first, int last);

// Sets missing in *x (and in *also, when not null) the samples of gap.marker beside `gap`
// that lie inside the stretch of s > threshold around the gap (above); `samples` are the
// marker's samples before detection (*x must be missing over `gap`). At most `max_extent`
// samples are cut on each side. Returns the number of samples cut. Sizes must agree
// (CHECKed: a programmer error).
int ExtendRoughRun(const Gap& gap, const MarkerTrajectories& samples, const MarkerTrajectories& reference,
                   double threshold, int max_extent, MarkerTrajectories* x, MarkerTrajectories* also = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_ROUGH_RUN_EXTENSION_H_
