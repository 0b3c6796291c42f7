// Marker gaps and their refill from a reference path (thesis 3.3.4, Algorithm 3) — the
// building blocks of marker repair (issue 4).
//
// A gap is a maximal run of missing samples of one marker, frames [first, last]
// inclusive. Refill: with X the original path and R a reference path of the same marker
// (e.g. markers reconstructed from a robust kinematic solve), the offset D = X - R is
// known at the frames around the gap; the fill is R plus a cubic Hermite offset that
// matches D and its velocity D' at both ends:
//   X(t) = R(t) + H(t),  H(s-1) = D(s-1), H'(s-1) = D'(s-1), H(e+1) = D(e+1), H'(e+1) = D'(e+1)
// so the filled path is C1-continuous with the original at both edges and moves like the
// reference inside. Velocities (length units per frame) are the slope of a least-squares
// line through D at up to `edge_samples` valid frames beyond each edge: with 2, the
// thesis' backward/forward difference; with 1 (or when only one sample is valid) zero, so
// the fill blends the two edge offsets and is C0 at the edges, moving like the reference.
// The repair uses 1: measured on real takes with damage (issue 16; BENCHMARKS.md), any
// extrapolated offset velocity made fills worse, and the thesis' two-sample difference on
// a jittery marker, scaled by the span in the tangent, threw short fills 2-4x further off
// than the noise itself. Velocities are clamped componentwise to +-velocity_clamp (thesis:
// keeps the fill from straying when the two paths' speeds differ). D itself is the edge
// sample's, so the fill always meets the data. Degenerate gaps, as in the thesis: a gap that runs
// to the end uses D(e+1) = D(s-1), D'(e+1) = 0; one at the start D(s-1) = D(e+1),
// D'(s-1) = 0; a marker missing all take takes the reference as it is.
#ifndef MOCAPSOLVE_SIGNAL_GAP_FILL_H_
#define MOCAPSOLVE_SIGNAL_GAP_FILL_H_

#include <limits>
#include <vector>

#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct Gap {
  int marker = 0;
  int first = 0;  // First missing frame.
  int last = 0;   // Last missing frame (inclusive).
  int length() const { return last - first + 1; }
};

// Every gap of every marker, ordered by marker then frame.
std::vector<Gap> FindGaps(const MarkerTrajectories& markers);

struct GapFillOptions {
  // Componentwise clamp of the offset velocities at the gap edges, in the markers' length
  // units per frame; infinity = no clamp.
  double velocity_clamp = std::numeric_limits<double>::infinity();
  // Samples beyond each edge that the offset velocity is fitted to (a least-squares
  // line; 2 = the thesis' one-sided difference).
  int edge_samples = 2;
};

// Fills `gap` of *markers from the same marker (same index) of `reference`, which must
// have the same frame count and be valid over the gap and at the edges used. Errors (one
// line) on mismatched sizes or a reference sample missing where it is needed.
Status FillGapFromReference(const Gap& gap, const MarkerTrajectories& reference,
                            const GapFillOptions& options, MarkerTrajectories* markers);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_GAP_FILL_H_
