// Samples of a labelled take that the body cannot have put where they are: a label the lab
// gave to a point off the body (a marker fallen off, a point on the floor or a prop). Used
// to make synthetic labelling takes (bench/label_benchmarks.cc): the motion they are made
// from is solved without these samples, so that it does not follow them (real
// nick_freeform_001's RTOE lies 0.8-1.4 m from its ankle marker from frame 975 on; the
// least-squares solve dragged the right leg toward it and back as it came and went, and
// the synthetic leg jumped up to 1.5 m between frames).
//
// Pose-free bound from the skeleton alone: with c the lowest common ancestor of the joints
// a and b that markers m and n ride on, m's position in c's frame is its first step v_m
// (the offset of c's child toward a, or m's offset z_m when a = c) plus the rest of the
// way, no longer than r_m (the bones below that child, then |z_m|; 0 when a = c), so
//   |x_m - x_n| <= B_mn = |v_m - v_n| + r_m + r_n.
// Pairs whose path crosses a joint with animated translation, and markers with more than
// one attachment, have no bound. In each frame, a pair with |x_m - x_n| > B_mn + tolerance
// is violated; the marker in most violated pairs is flagged and its pairs dropped, until
// none is violated. Ties (one violated pair: which end is off?) go against the marker with
// fewer joint mates (markers on its joint) at their model distance within the tolerance,
// then the larger summed excess: nick's RTOE, alone on its foot in those frames, against
// RANK, held at its distances by the three other shin markers.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_LABEL_OFF_BODY_SAMPLES_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_LABEL_OFF_BODY_SAMPLES_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

// observed[f][m]: skeleton units, non-finite = missing. Returns [f][m]: 1 = off the body.
// tolerance: skeleton units (skin and fit errors).
std::vector<std::vector<char>> OffBodySamples(const Skeleton& skeleton, const MarkerSet& markers,
                                              const std::vector<std::vector<Eigen::Vector3d>>& observed,
                                              double tolerance);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_LABEL_OFF_BODY_SAMPLES_H_
