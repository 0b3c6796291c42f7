// Joints whose template locks one rotation axis that nothing below them makes up.
//
// A template skeleton gives some joints two rotation dofs: an ASF foot turns about its
// ankle axis and its vertical (dorsiflexion, toe-in/out) but not about its own long axis
// (heel to toe). With the knee a one-dof hinge, that roll is then the shank's, set by the
// hip's twist and the thigh's markers; a lab whose foot markers span the forefoot's width
// (a first and a fifth metatarsal head) sees the foot roll on its own (inversion in the
// sprint's swing, eversion in stance), and a model that cannot follow leaves every foot
// marker 10-20 mm off with all markers seen, 25-30 mm off when one is left out
// (BENCHMARKS.md, issue 36, h31n). A clavicle also has two dofs, but the ball joint below
// it (the humerus) makes up its missing axis, so freeing it only adds a redundant dof.
//
// LockedAxisJoints: joint j with exactly two rotation dofs, no joint below it with three
// (nothing below makes the third axis up), and at least `min_markers` markers on j or
// below it (any attachment; three non-collinear points are the least that observe a
// rotation about every axis).
// FreeLockedAxes: the same skeleton with each such joint's missing axis c inserted between
// its two (a, b) -> (a, c, b): R_j = R_a(alpha) R_c(gamma) R_b(beta) is the two-dof
// joint's rotation at gamma = 0, and the middle angle is the one whose +-90 degrees gimbal
// lock is farthest from there; its rotation channel is added, its limit (when the joint
// has limits) is unlimited. Offsets, rest rotations and every other joint are unchanged,
// so a marker set or a motion of the one fits the other.
// Whether the freed skeleton is kept is decided by prediction (fit_skeleton_task.cc).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LOCKED_AXES_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LOCKED_AXES_H_

#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

std::vector<int> LockedAxisJoints(const Skeleton& skeleton, const MarkerSet& markers, int min_markers = 3);

// Errors: a joint index out of range or without exactly two rotation dofs; those of
// Skeleton::Create.
Status FreeLockedAxes(const Skeleton& skeleton, const std::vector<int>& joints, Skeleton* freed);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_LOCKED_AXES_H_
