// A small procedural character and walk-like clip that the project makes itself: the
// bundled default for scripts/demo.sh and a fallback fixture for tests and benchmarks.
// 20 joints, human proportions in centimetres, Y up, facing +Z; the clip swings legs and
// arms sinusoidally while the root moves forward (about 1 m/s) and bobs.
#ifndef MOCAPSOLVE_KINEMATICS_DEMO_CHARACTER_H_
#define MOCAPSOLVE_KINEMATICS_DEMO_CHARACTER_H_

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

Skeleton MakeDemoSkeleton();
Motion MakeDemoWalk(const Skeleton& skeleton, int num_frames, double frame_rate);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_DEMO_CHARACTER_H_
