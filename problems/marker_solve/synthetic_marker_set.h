// Synthetic marker sets: markers placed around the bones of any skeleton, for tests,
// demos (`mocapsolve markers --markerset=auto:N`) and ground-truth experiments.
//
// Every joint j that has a child joint or an end site gets `per_joint` markers, each
// rigidly attached to j (one attachment, weight 1), labelled "<joint>_<k>". The bone of
// j is b_j, the longest of its children's offsets (child translations / end-site
// offsets, all in j's frame); L = |b_j|, or, for a zero-length bone (the ASF root's
// children start at the root), the median non-zero bone length of the skeleton along
// j's +Y axis. Marker k sits at
//
//   z_k = u_k b + r_k L (cos(theta_k) e1 + sin(theta_k) e2)            (joint j's frame)
//
// with (e1, e2) an orthonormal basis perpendicular to b, u_k in [0.2, 0.8] along the
// bone, radius r_k in [0.15, 0.35] (relative to L), theta_k = theta_0 + 2 pi k / 3 + a
// jitter below 20 degrees for k < 3 and random for k >= 3. All draws come from a
// SplitMix64 stream seeded with `seed` (the same set on every platform). Because the
// first three markers of a joint sit on rays more than 80 degrees apart around the bone
// at positive radii, a joint's markers are never collinear (for per_joint >= 3), so
// they fix the joint's rotation.
//
// Length units are the skeleton's.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SYNTHETIC_MARKER_SET_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SYNTHETIC_MARKER_SET_H_

#include <cstdint>

#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

// per_joint < 1, or a skeleton whose joints all lack children and end sites, gives an
// empty set.
MarkerSet MakeSyntheticMarkerSet(const Skeleton& skeleton, int per_joint, uint32_t seed);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SYNTHETIC_MARKER_SET_H_
