// Finding the body in one frame of unlabelled points, with no assumption about its pose
// (no T-pose, any position and heading): the start of marker labelling and its recovery
// after a loss (marker_labeller.h).
//
// Rigid clusters: the markers whose attachment is one joint (weight 1) ride rigidly on
// that joint, at offsets z_m in its frame. For a cluster of >= 3 markers, the triangle of
// its markers (a, b, c) with the largest area is looked for in the cloud: every triple of
// points (i, j, k) whose pairwise distances match |z_a - z_b|, |z_b - z_c|, |z_a - z_c|
// within `cluster_tolerance` gives, by the least-squares rigid fit of (z_a, z_b, z_c) onto
// (u_i, u_j, u_k) (Umeyama without scale), a hypothesis world_from_joint; it scores by the
// cluster's markers that land within the tolerance of a point. The best hypotheses of the
// largest clusters each place the whole body: the subject's mean pose (identity rotations
// without one) moved rigidly so that the joint sits where the hypothesis puts it. Besides
// them, the mean pose centred on the cloud in each of the 24 axis-aligned orientations.
//
// Each placement is refined by iterated matching and solving (ICP on the kinematic
// model): predict every marker, match points one to one within a gate (gated_assignment.h;
// the gate shrinks geometrically from 16 x `gate` to `gate` over the iterations), solve the pose from the
// matched points (MarkerFrameSolver, warm-started). A placement scores
//   sum over markers of min(e_m^2, 1)   (e_m = |u - p_m| / gate of its match; 1 when empty),
// and the lowest wins; it is then polished (RestartLimbs, then PolishMatches, below).
// The body is found when at least `accept_fraction` of the markers
// are matched within `gate`, at an RMS distance of at most `max_rms` (measured on the
// five real takes with their own subjects: 94-100 % matched at 3.7-10.3 mm; with another
// person's or marker set's subject: 61-83 % at 18.4-22.7 mm). Lengths in skeleton units.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_LABEL_LABEL_ACQUISITION_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_LABEL_LABEL_ACQUISITION_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "problems/marker_label/gated_assignment.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

struct AcquisitionOptions {
  double cluster_tolerance = 0.0;  // Skeleton units (> 0): pair distances and cluster inliers.
  double gate = 0.0;               // Skeleton units (> 0): the final matching gate.
  double accept_fraction = 0.85;   // Of the marker set's markers, matched within `gate`.
  double max_rms = 0.0;            // Skeleton units (> 0): the matches' RMS distance at most.
  int iterations = 12;             // Match-and-solve rounds per placement.
  int hypotheses_per_cluster = 3;  // Best cluster placements refined, per cluster.
  int max_clusters = 4;            // Largest clusters tried.
};

// The markers riding rigidly on one joint.
struct RigidCluster {
  int joint = -1;
  std::vector<int> markers;
  std::vector<Eigen::Vector3d> offsets;  // In the joint's frame.
};
// Clusters of >= 3 markers, largest first.
std::vector<RigidCluster> RigidClusters(const MarkerSet& markers);

struct Acquisition {
  bool found = false;
  Pose pose;                  // The best placement, refined.
  GatedAssignment matches;    // Its matches within `gate`.
  int matched = 0;            // Markers matched.
  double rms = 0.0;           // RMS distance of the matches (skeleton units).
  int placements = 0;         // Placements refined.
};

// `start` is the pose whose joint rotations placements start from (the subject's mean
// pose; its root is replaced). `solver` is the caller's (its options decide priors).
Acquisition AcquireBody(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<RigidCluster>& clusters,
                        const Pose& start, const std::vector<Eigen::Vector3d>& points,
                        const AcquisitionOptions& options, MarkerFrameSolver* solver);

// Local search over one frame's matches (`matches` made at `gate` around the model at
// *pose): exchanges of the points of two matched markers (within 3 gates of each other),
// cycles of three (within 2 gates), a marker taking a free point within 3 gates (and its
// own point passing to a neighbour); each move kept when the pose solved from the moved matches lowers
//   sum over markers of min(|x_m - M_m(pose)|^2, gate^2)   (an empty marker: gate^2)
// below keep_ratio times its value (0.99 = by more than 1 %; both callers). The fixed
// point of match-and-solve rounds can hold the markers of a
// foot or a wrist in a rotated order the rounds cannot leave. free_points: moves that
// give a marker a point no marker has are tried too. rematch: the matches are then made
// again around the polished pose (else the moved matches are kept as they are, the
// confidences untouched). *pose: the polished pose. Returns whether a move was kept.
bool PolishMatches(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<Eigen::Vector3d>& points,
                   double gate, bool rematch, bool free_points, double keep_ratio, MarkerFrameSolver* solver,
                   Pose* pose, GatedAssignment* matches);

// Each limb (the subtree of every joint but the root that carries two or more markers: a
// leg, a shin and foot, an arm, a hand, the head) started again: its joints set to
// `start`'s rotations, its markers' matches dropped, then matched among the points the
// other markers leave free in rounds of match-and-solve (the gate shrinking from 4 gates
// to one), the rest of the body held by its own matches. A limb's new matches are kept
// when they lower SolvedCost below keep_ratio times its value. Match-and-solve from a
// whole-body placement can settle with a limb's markers each on its neighbour's point (a
// chain shifted along an arm: a cycle longer than PolishMatches' moves) or with a hand
// turned half a turn (its inner and outer markers exchanged), a basin a solve warm-started
// there does not leave. The kept
// matches are as made (distances and confidences untouched). Returns whether one was kept.
bool RestartLimbs(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<Eigen::Vector3d>& points,
                  const Pose& start, double gate, double keep_ratio, MarkerFrameSolver* solver, Pose* pose,
                  GatedAssignment* matches);

// The cost PolishMatches compares: sum over markers of min(|x_m - M_m(pose)|^2, gate^2)
// (an empty marker: gate^2) once the pose is solved from the matched points
// (point_of_marker[m]: an index into `points`, -1 = none), warm-started at *pose (updated).
double SolvedCost(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<Eigen::Vector3d>& points,
                  const std::vector<int>& point_of_marker, double gate, MarkerFrameSolver* solver, Pose* pose);

// How far the points given to markers riding on one joint are from the joint's shape, under
// two labellings of the same frames: the sum over pairs (m, n) of markers attached to one
// joint only (weight 1), one of them `involved`, of the RMS over the frames of
//   |u_m - u_n| - |z_m - z_n|        (u: the pair's points, z: their offsets on the joint),
// frame i's points given by kept[i] and moved[i] (point_of_marker into points[i]); a pair
// counts in the frames where both labellings give both of its markers a point. Model-free
// of the pose: a marker alone on a free joint can reach a neighbour's point in a whole-body
// fit, but its point does not keep the neighbour's distances to the neighbour's joint mates.
void JointShapeErrors(const MarkerSet& markers, const std::vector<std::vector<Eigen::Vector3d>>& points,
                      const std::vector<std::vector<int>>& kept, const std::vector<std::vector<int>>& moved,
                      const std::vector<char>& involved, double* kept_error, double* moved_error);

// Every marker's model position at `pose` (#M, skeleton units).
std::vector<Eigen::Vector3d> ModelMarkerPositions(const Skeleton& skeleton, const MarkerSet& markers, const Pose& pose);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_LABEL_LABEL_ACQUISITION_H_
