// Marker association: which body segment each marker of a take rides on, from the take's
// data alone, for a marker protocol nobody mapped (labels in any language or none).
//
//  1. Non-marker points. A point observed in fewer than 10 % of the frames, or whose median
//     distance to the body (the per-frame median of all points) exceeds 6 times the median
//     point's (a joint angle or force in a lab's model outputs, a point at the origin), is
//     excluded and reported with the reason; so is, after step 4, a point that keeps its
//     distance to no other (smallest pair spread > `max_lone_spread`: nothing rigid moves
//     with it). (The C3D reader already sets apart the POINT groups' model outputs.)
//  2. Up axis. Per sampled frame, the points' extent along each file axis; the axis with the
//     largest median extent is vertical (a body is taller than it is wide, most of a take).
//     Its sign: the bottom of a body is two feet apart, its top one head; the horizontal
//     spread of the points in the lowest 12 % of the extent against the highest 12 %
//     (median over frames), and where that is not clear (within 20 %) the floor: the lowest
//     point's height varies less over the take than the highest's.
//  3. Units. The median vertical extent E (file units) is a body 0.9-2.3 m tall: the file's
//     unit when E in it falls in [0.8, 2.5] m, else the first of mm, cm, m, inch that does
//     (nearest 1.6 m); none: an error that names the extent.
//  4. Rigid clusters (rigid_marker_clusters.h).
//  5. Layout. Heights h (above the floor: the 2nd percentile of the lowest point, divided by
//     E) and, in the pelvis' frame, side and forward coordinates, each a median over frames.
//     The pelvis is the cluster of >= 2 markers at h in [0.38, 0.72] that is widest and most
//     central; its horizontal principal axis is the left-right line, and forward is the
//     side where its markers are wider apart (the anterior iliac spines are wider than the
//     posterior ones) and toward which the feet point (toes ahead of the shank); left =
//     up x forward. The head is the highest central cluster (h > 0.78); the chest is every
//     other central cluster between them. On each side, the foot is the lowest cluster
//     (h < 0.2), the shin and the thigh follow up the leg, each the cluster most rigidly
//     joined to the previous one (the smallest spread of any cross pair: the joint's
//     markers) within the leg's heights; the upper arm is the side's cluster above the
//     pelvis most rigidly joined to the chest (or head), the forearm and hand follow it the
//     same way. A cluster left over takes the role of the cluster it moves most rigidly with.
//  6. Confidence per marker, in [0, 1]: its cluster's separation (own mean spread against
//     the nearest other cluster's), times 0.6 for a one-marker cluster, 0.5 for a leftover
//     role, 0.7 when the side is unclear (|side| < 3 cm), times 0.5 when a side word in its
//     label (L..., R..., left, right) disagrees with the side found (1.0 when it agrees).
// Roles are named as humanoid_roles.h names joints (pelvis, chest, head, left_thigh,
// left_shin, left_foot, left_upper_arm, left_forearm, left_hand, right_...).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_ASSOCIATION_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_ASSOCIATION_H_

#include <string>
#include <utility>
#include <vector>

#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"
#include "kinematics/units.h"
#include "problems/marker_solve/rigid_marker_clusters.h"

namespace mocapsolve {

struct MarkerAssociationOptions {
  RigidClusterOptions clusters;
  double max_lone_spread = 0.06;  // Metres (step 1).
};

struct AssociatedMarker {
  std::string label;
  std::string role;         // "" when none was found.
  double confidence = 0.0;  // [0, 1].
  int cluster = -1;         // Index into MarkerAssociation::clusters.
  double height = 0.0;      // h, relative to the body height (median over frames).
  double side_m = 0.0;      // Along left, metres (median over frames).
};

struct MarkerAssociation {
  LengthUnit unit;              // Of the take's numbers: the file's, or detected.
  bool unit_from_data = false;  // The file's unit did not make a body (or it had none).
  int up_axis = 2;              // File axis (0 x, 1 y, 2 z) that points up ...
  int up_sign = 1;              // ... with this sign.
  double height_m = 0.0;        // Median vertical extent of the points.
  std::vector<AssociatedMarker> markers;                      // The kept points, in file order.
  std::vector<std::pair<std::string, std::string>> excluded;  // (label, reason).
  std::vector<std::vector<std::string>> clusters;             // Labels per rigid cluster.

  const AssociatedMarker* Find(const std::string& label) const;
  std::string UpName() const;  // "+z", "-y", ...
};

// Errors (one line, naming `path`): no frames or no observed point, fewer than 6 points kept,
// an extent that makes no body in any unit, no pelvis-like cluster.
Status AssociateMarkers(const MarkerTrajectories& take, const std::string& path,
                        const MarkerAssociationOptions& options, MarkerAssociation* association);

// -1 left, +1 right, 0 none: a side word in a marker label (LASI, L_IAS, LeftKnee, "r should").
int LabelSide(const std::string& label);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_MARKER_ASSOCIATION_H_
