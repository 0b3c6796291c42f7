// Motions and marker trajectories as pyramid signals, and band editing / data filtering
// on them (Huang, Boulic & Thalmann, eq. 7 and section 5).
//
// Motion channels (#F rows, 7 #J columns): for joint j, columns 4j..4j+3 hold its local
// rotation as a sign-continuous unit quaternion (w, x, y, z), and columns 4#J + 3j ..
// 4#J + 3j + 2 its local translation t_j(f) (file units). Rotations are filtered as
// rotations, not as Euler channels: each band is a linear combination of quaternions of
// one hemisphere-continuous series (q and -q being one rotation, the series is first made
// sign-continuous, MakeSignContinuous), and the collapsed 4-vector is projected back onto
// the unit sphere, q' = s / |s| (for a blend of two rotations this is nlerp, which is what
// eq. 6 means for rotations). This has no singularity, so a root that turns many times
// filters as well as a knee. (An exp-map displacement from one reference rotation was
// tried first: its rotation vectors cannot be kept continuous when a joint turns through
// 2 pi about a wandering axis, where the exp map collapses a sphere to the identity.)
// With every weight 1 the collapse returns the same unit quaternions, so reconstruction
// stays exact. A collapsed 4-vector of norm < 1e-9 (only possible with extreme band
// weights) keeps the input rotation of that frame.
//
// Marker channels (#F rows, 3 #M columns): the marker positions in the file's unit and
// axes. Missing samples (NaN + mask, marker_trajectories.h) are filled for the pyramid
// only: linearly between the nearest valid samples of the same marker, held constant
// before the first and after the last valid one (0 for a marker with no valid sample);
// after filtering they are masked back, so a missing sample stays missing and a valid
// one stays valid. Residuals and camera masks are copied unchanged.
#ifndef MOCAPSOLVE_SIGNAL_MOTION_PYRAMID_H_
#define MOCAPSOLVE_SIGNAL_MOTION_PYRAMID_H_

#include <vector>

#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/status.h"
#include "signal/laplacian_pyramid.h"

namespace mocapsolve {

// The rotations of frame `frame` (every joint's hemisphere reference).
QuaternionVector ReferenceRotations(const Motion& motion, int frame);

// Motion -> channels. Each joint's quaternion series is made sign-continuous and then,
// as a whole, given the sign whose anchor_frame sample is nearer reference[j] (so two
// motions blended at that frame lie in one hemisphere). #J = reference.size().
void MotionToSignal(const Motion& motion, const QuaternionVector& reference, int anchor_frame,
                    Signal* signal);
// Channels -> motion (frame_rate copied from the argument); `fallback` supplies the
// rotation of a frame whose 4-vector is degenerate (see above).
void SignalToMotion(const Signal& signal, const Motion& fallback, double frame_rate,
                    Motion* motion);

// Filled channels of the trajectories (see above); the mask stays in the trajectories.
void MarkersToSignal(const MarkerTrajectories& trajectories, Signal* signal);

// Band editing (eq. 7) of a motion: pyramid of options.levels levels (0 = as many as
// the clip allows), collapsed with `weights` (N + 1 values, w_0 the finest band; empty
// = all ones). Fails on a clip too short
// for the levels or a wrong weight count.
Status FilterMotion(const Motion& motion, const PyramidOptions& options,
                    const std::vector<double>& weights, Motion* filtered);
// Same for marker trajectories; missing samples stay missing.
Status FilterMarkers(const MarkerTrajectories& trajectories, const PyramidOptions& options,
                     const std::vector<double>& weights, MarkerTrajectories* filtered);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_MOTION_PYRAMID_H_
