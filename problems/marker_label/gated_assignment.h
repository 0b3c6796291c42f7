// One frame's points matched one to one to the markers that predict them, each match
// gated and scored (the per-frame step of marker labelling, marker_labeller.h).
//
// Input: a prediction p_m and a gate g_m > 0 per marker (a non-finite p_m: no
// prediction, the marker takes no point) and the frame's points u_k (any order, any
// number). With normalized distances e_mk = |u_k - p_m| / g_m, point k is a candidate for
// marker m when e_mk < 1. The frame's markers and points are matched one to one,
// minimizing
//   sum over matched pairs e_mk^2  +  (number of markers left empty) * 1,
// so a marker stays empty rather than take a point at or beyond its gate (the cost of
// leaving a label empty is the cost of a match at the gate). The candidate graph splits
// into independent groups (markers and points linked by candidate pairs); a group of one
// marker and one point is matched directly, larger groups exactly by the Hungarian method
// (MinimumCostAssignment) with one "empty" column per marker.
//
// Confidence of a match (m, k), in [0, 1]:
//   c = (1 - e_mk^2) * max(0, 1 - e_mk / e_alt),
// e_alt the competitor's normalized distance. In a group of up to 6 markers, from the
// matching's margin: e_alt = sqrt(e_mk^2 + D), D what the group's best matching costs more
// without the pair (m, k) (so one other candidate point i of m alone gives e_alt = e_mi,
// as below, and a marker n that could take k but has its own nearer point does not make
// the match doubtful: a hand marker next to a wrist marker, each tracked, real
// nick_freeform_001 97.78 -> 98.49 %, synthetic 97.56 -> 98.52 %). In larger groups (the
// wide gates of finding the body), the smallest normalized distance of a competitor:
// another candidate point of m, or another marker n for which k is a candidate (e_nk);
// e_alt = infinity without one. A match near its gate or with a competitor about as
// close scores low. A "conflict" is a
// marker whose nearest candidate point went to another marker, or that a competitor
// claimed too (the one-to-one assignment decided between them: nearest-point labelling
// would have given two markers the same point or swapped them).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_LABEL_GATED_ASSIGNMENT_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_LABEL_GATED_ASSIGNMENT_H_

#include <vector>

#include <Eigen/Core>

namespace mocapsolve {

struct GatedAssignment {
  std::vector<int> point_of_marker;  // #M: the matched point's index, -1 = empty.
  std::vector<double> confidence;    // #M: of the match (0 when empty).
  std::vector<double> distance;      // #M: |u_k - p_m| of the match (NaN when empty).
  std::vector<bool> conflict;        // #M: see the header comment.
};

// predicted and gate: #M each (skeleton units); points: the frame's points.
void AssignGated(const std::vector<Eigen::Vector3d>& predicted, const std::vector<double>& gate,
                 const std::vector<Eigen::Vector3d>& points, GatedAssignment* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_LABEL_GATED_ASSIGNMENT_H_
