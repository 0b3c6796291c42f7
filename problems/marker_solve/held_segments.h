// Segments no marker observes (a sparse protocol: Plug-in Gait lower body, Helen Hayes /
// Davis). Joint j is observed when a marker rides on j or on a joint below it (its rotation,
// and its bone's scale, move that marker); otherwise no marker pulls it, so it stays where
// it starts: the template's rest in a subject fit, whose subject then keeps the template's
// mean pose for it (fit_skeleton_task.h), and that mean pose in a solve (InitialPose,
// sequence_solver.h, starts such joints there). HeldSegments names those joints by
// the tops of their held subtrees (a held joint whose parent is observed: "upperback" for a
// lower-body set's whole upper body). MissingSegments checks the segments a delivered
// character needs its take to observe (the pelvis and, per side, thigh, shin and foot,
// found by humanoid_roles.h): a leg segment must carry a marker or hold one below it; the
// pelvis a marker of its own (on its joint, or a child of it that leads to no leg), as the
// legs' markers place the root through the hips but hold neither its tilt nor its twist.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_HELD_SEGMENTS_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_HELD_SEGMENTS_H_

#include <string>
#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

// Per joint: some marker of `markers` rides on it or on a joint of its subtree.
std::vector<bool> ObservedJoints(const Skeleton& skeleton, const MarkerSet& markers);

// The tops of the unobserved subtrees, in joint order, and how many joints they hold.
struct HeldSegments {
  std::vector<std::string> tops;
  int joints = 0;
};
HeldSegments FindHeldSegments(const Skeleton& skeleton, const MarkerSet& markers);

// The joints an attach round may put a marker on (calibration.h, candidate_joints): all but
// those of a held subtree that is more than an end segment (a joint below its top has
// joints below it). In the motion an attach round compares a marker with, such a subtree
// does not move against its parent, so every marker ties with it and the nearer bone wins:
// a Davis set's C7 went on a clavicle, an acromion on the neck, and the clavicle then swung
// the whole (unobserved) arm to follow that one marker. A held end segment stays allowed
// (a leaf: a finger, the toes; a hand with its fingers, a foot with its toes): a marker
// there moves that end and nothing else, and a full-body take whose association left a
// hand's or foot's markers on the forearm or shin needs the attach rounds to move them
// there (nick_freeform_001 renamed: its hands excluded, 12.95 mm). Empty when nothing is
// excluded (every joint allowed).
std::vector<int> AttachableJoints(const Skeleton& skeleton, const MarkerSet& markers);

// The needed segments `markers` leaves unobserved, one entry each: "left_foot (lfoot; the
// template puts LHEE, LTOE there)", naming `template_markers`' labels on that joint and
// below it. Empty when every needed segment is observed, or the skeleton is no humanoid.
std::vector<std::string> MissingSegments(const Skeleton& skeleton, const MarkerSet& markers,
                                         const MarkerSet& template_markers);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_HELD_SEGMENTS_H_
