// Label swaps undone (issue 16 item 1): two or more labels that exchange trajectories for
// an interval are relabelled instead of cut and refilled.
//
// Input: the samples x_fm, the typical predictions T_fm and take-wide gates t_m of the
// marker residual model (marker_residual_model.h; T is the reference's reconstruction plus
// the marker's typical residual; written P below). In frame f, a sample x_fm that is an
// outlier for its own label,
//   |x_fm - P_fm| > t_m,
// is claimed by the nearby label n (|P_fn - P_fm| <= radius) that minimizes
// |x_fm - P_fn| / t_n, if
//   |x_fm - P_fn| <= t_n                   (it fits n as n's own samples do),
//   |x_fm - P_fn| <= margin |x_fm - P_fm|  (much better than its own label), and
//   label n has no sample of its own that fits it (n missing, or x_fn outlying for n):
// a point next to a well tracked marker is a ghost, not a swap, and stays an outlier.
// Claims are one to one per frame (the nearest claim on a label wins); an exchange is
// completed (n -> m too, when n's outlying sample is within margin of its own distance
// from m's prediction and nobody claims m). A claim m -> n counts only in runs of at least
// min_frames consecutive frames, so single noisy frames are not relabelled. The reference
// drifts toward the swapped labels once a swap has begun (a robust solve still partly
// follows two wrong markers of one bone), so the claims are then carried forward from a
// swap's onset and backward from its end while, by continuity (each relabelled trajectory
// extrapolated at constant velocity from its two previous frames), the exchange costs
// less than margin times the identity, and the identity costs more than the smallest gate
// of the labels involved.
// The reference cannot see every swap: from the take's first frame it follows the swapped
// labels (its start fits them), and on a bone that one marker pins (LFIN on the thumb) it
// turns the bone to follow the swap. Exchange events need no reference: labels a and b,
// within radius of each other, exchange between frames f - 1 and f when, with E_l(f) the
// position of label l extrapolated at constant velocity from frames f - 1 and f - 2,
//   |x_fa - E_b| + |x_fb - E_a| <= event_margin (|x_fa - E_a| + |x_fb - E_b|),
// the identity's cost exceeds t_a + t_b, and the same holds backward (f - 1 extrapolated
// from f and f + 1). Over each run of frames where both labels are observed, the events
// cut the run into segments whose labellings alternate; of the two alternations, the one
// whose exchanged segments gain more against the typical predictions,
//   sum over its exchanged segments and frames of |x_a - T_a| + |x_b - T_b| - |x_a - T_b| - |x_b - T_a|,
// is kept (a segment the reference followed is outweighed by the ones it did not), and it
// replaces the pair's claims in that run, provided both trajectories are smooth inside its
// exchanged segments (|x_f - 2 x_(f-1) + x_(f-2)| <= t_l): a label that also jumps there
// (overlapping swaps with a third label) forms a chain the pair's events do not describe. A run without events keeps the claims above (a
// swap that begins inside a gap shows no event at its start).
// The claims are then carried once more by continuity, forward and backward, only into
// frames where one of the exchanged labels has no sample (the frames of a swap a gap
// hides, which no event sees), each cycle of labels (a -> b -> a) on its own: a label is
// continued from its last two relabelled samples within 15 frames (E = x_g + (x_g - x_h) |f - g|),
// and the exchange must also fit the typical predictions no worse than the identity,
//   sum |x_from - T_to| <= sum |x_from - T_from|,
// since two nearby markers may lie closer than the extrapolation's error.
// Then, per frame, label n takes sample x_fm; a label that gave its sample
// away and received none becomes missing (a swap that begins or ends inside a gap: the
// other label's sample was missing), to be filled as any gap. Chains of more than two
// labels are undone the same way (by claims only: their events are not pairwise).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_SWAP_DETECTION_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_SWAP_DETECTION_H_

#include <utility>
#include <vector>

#include "kinematics/marker_trajectories.h"
#include "problems/marker_repair/marker_residual_model.h"

namespace mocapsolve {

struct SwapDetectionOptions {
  double radius = 0.0;  // Skeleton units: labels whose predictions are this close may swap.
  double margin = 0.5;  // The claimed label's distance at most this fraction of the own one.
  int min_frames = 2;   // Frames a claim must persist.
  double event_margin = 0.25;  // An exchange event's exchanged cost at most this fraction of the identity's.
};

// One interval over which the same labels were exchanged.
struct MarkerSwap {
  int first = 0, last = 0;                    // Frames, inclusive.
  std::vector<std::pair<int, int>> from_to;   // Sample of label `first` now labelled `second`.
  double distance_before = 0.0;  // Mean over the interval's samples of |x - P| to the old label.
  double distance_after = 0.0;   // ... to the new label (skeleton units).
};

// Relabels the swapped samples of *x in place and returns the swaps, ordered by first frame.
std::vector<MarkerSwap> UndoSwaps(const MarkerResidualModel& model, const SwapDetectionOptions& options,
                                  MarkerTrajectories* x);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_SWAP_DETECTION_H_
