// Marker association: which body segment each marker of a take rides on, from the take's
// data alone, for a marker protocol nobody mapped (labels in any language or none).
//
//  1. Non-marker points, before the up axis and the unit are known (a stray point moves the
//     lowest or highest point those steps read), with scale-free rules; the body's size B
//     is the median point's median distance to the per-frame median point (about 0.45 m).
//     Excluded and reported with the reason, in this order: a point observed in fewer than
//     10 % of the frames; one whose median distance to the per-frame median point exceeds
//     3.5 B (far from the body); one whose median distance to the file's origin is below
//     0.2 B while the body's centre is over B from it (a lab's model output written as a
//     point: joint angles in degrees, forces in N/kg, powers in W/kg sit at the origin,
//     wherever the body walks); one whose smallest pair spread (rigid_marker_clusters.h,
//     in units of B) exceeds 0.13 B (nothing moves rigidly with it: a moment in N mm/kg);
//     one still (it moves less than a tenth of the median point) that keeps over 0.75 B from
//     every point of the body: a point that moves, or a still one within 0.75 B of the body
//     (a chain: a squat's planted foot beside its still shin, beside the moving knee); a
//     point that does not move at all (the same numbers in every frame, which no tracked
//     marker gives) is of the body only within 0.75 B of a moving point. After step 4, also
//     a point that keeps its distance to no other (smallest pair spread > `max_lone_spread`,
//     metres). Virtual
//     points that move with the body (a centre of mass, a joint centre) are kept; a fit
//     attaches them like markers. (The C3D reader already sets apart the model outputs
//     its POINT groups or Plug-in Gait names mark.)
//  2. Up axis. Per sampled frame, the points' extent along each file axis; the axis with the
//     largest median extent is vertical (a body is taller than it is wide, most of a take).
//     Its sign: the bottom of a body is two feet apart, its top one head; the horizontal
//     spread of the points in the lowest 12 % of the extent against the highest 12 %
//     (median over frames), and where that is not clear (within 20 %) the floor: the lowest
//     point's height varies less over the take than the highest's.
//  3. Units. The median vertical extent E (file units) is a body 0.9-2.3 m tall: the file's
//     unit when E in it falls in [0.3, 2.5] m (part of a body too: a lower-body set, a
//     child), else the first of mm, cm, m, inch that does (nearest 1.6 m); none: an error
//     that names the extent.
//  4. Rigid clusters (rigid_marker_clusters.h).
//  5. Layout. Heights h (above the floor: the 2nd percentile of the lowest point, divided by
//     the stature: E, or, when the top is no head, the top's height over 0.86: a gait set
//     without head markers ends at C7, found by an acromion beside it, in the top band, in
//     another rigid cluster and moving nearly with it) and, in the hip band's frame, side
//     and forward coordinates, each a median over frames. That frame faces the band's
//     heading in a take that travels straight (a sprint's thighs swing wider fore and aft
//     than the hips are wide), else its principal axis is the left-right line. A cluster
//     below the knees with points over 0.12 m apart on both sides of the midline (planted
//     feet keep their distance, so they cluster) is split into its two sides.
//     The pelvis is the cluster of >= 2 markers at h in [0.38, 0.72] that is widest and most
//     central; its horizontal principal axis is the left-right line, and forward is the
//     side where its markers are wider apart (the anterior iliac spines are wider than the
//     posterior ones) and toward which the feet point (toes ahead of the shank); left =
//     up x forward. The head is the highest central cluster (h > 0.78); the chest is every
//     other central cluster between them. On each side, the foot is the lowest cluster
//     (h < 0.2), the shin and the thigh follow up the leg, each the cluster most rigidly
//     joined to the previous one (the smallest spread of any cross pair: the joint's
//     markers) within the leg's heights, read in the leg's stance (the frames where the
//     side's lowest leg point is within 0.06 of the floor: a sprint's feet are in the air
//     most of the take); the upper arm is the side's cluster above the
//     pelvis most rigidly joined to the chest (or head), the forearm and hand follow it the
//     same way; a side whose only such points sit at shoulder height (median h > 0.72: a
//     Helen Hayes / Davis acromion beside C7, no elbow or wrist marker) has no arm, and its
//     points join the trunk (chest). A cluster left over takes the role of the cluster it
//     moves most rigidly with.
//  6. Confidence per marker, in [0, 1]: its cluster's separation (own mean spread against
//     the nearest other cluster's), times 0.6 for a one-marker cluster, 0.5 for a leftover
//     role, 0.7 when the side is unclear (|side| < 3 cm, and no joint links it to a sided
//     leg cluster), times 0.5 when a side word in its label (L..., R..., left, right)
//     disagrees with the side found (1.0 when it agrees).
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
  // The excluded labels that are surely no markers (far from the body, at the file's
  // origin, nothing rigid with them); not those rarely seen or still (a foot at rest).
  std::vector<std::string> non_markers;
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
