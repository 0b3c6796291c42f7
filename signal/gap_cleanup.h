// Gap preprocessing before refill (thesis 3.3.4), in the thesis' order: first small
// tracks are removed, then small gaps are filled.
//
// A small track is a run of at most `max_track` valid samples with missing samples on
// both sides (a marker that flickers back for a few frames): too short to trust, it
// becomes part of the gap. A small gap is a gap of at most `max_gap` frames with valid
// samples on both sides: it is filled by the cubic Hermite through the edge samples with
// one-sided difference velocities (the "naive polynomial"), no reference needed.
#ifndef MOCAPSOLVE_SIGNAL_GAP_CLEANUP_H_
#define MOCAPSOLVE_SIGNAL_GAP_CLEANUP_H_

#include <functional>

#include "kinematics/marker_trajectories.h"

namespace mocapsolve {

// Returns the number of samples made missing.
int RemoveSmallTracks(int max_track, MarkerTrajectories* markers);
// The same, keeping every track that holds a sample `trusted` (frame, marker) accepts.
int RemoveSmallTracks(int max_track, const std::function<bool(int, int)>& trusted, MarkerTrajectories* markers);
// Returns the number of samples filled.
int FillSmallGaps(int max_gap, MarkerTrajectories* markers);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_GAP_CLEANUP_H_
