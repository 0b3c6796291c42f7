// Joints carried across whole-segment gaps: where every marker that observes a joint's
// rotation is missing, the joint moves in joint space across the gap instead of staying
// wherever a solve without data left it (the prior, the rest pose, its last value).
//
// Observers: marker m observes joint j when its position depends on j's rotation, i.e. j
// is one of m's influencing joints (MarkerSet::InfluencingJoints: the chains from the
// root to its attachment joints). A run of joint j is a maximal run of frames [s, e] in
// which j has lost its observers: at least 2 of them are missing, and fewer than 3 and
// fewer than half have a sample, for a joint that has observers at all (a joint no marker
// ever sees is left as it is; one observer gone alone is a marker's gap, which the fill
// from the solve handles better: on `mocapsolve evaluate`'s damage of CMU 02_01, carrying
// those too made the refill worse, 8.65 -> 9.36 mm mean). With every marker of a foot hidden, the foot and toe
// joints qualify, and so does the shank whose only markers left are a knee and a shin
// marker (measured on CMU 02_05: its solve from those two drifts 40-60 mm at the ankle).
// A joint whose parent is observed is observed too where the markers left on its own bone
// (attached to it alone) fix its degrees of freedom: the smallest singular value of their
// velocity Jacobian, rows e_k x v (v the marker's offset, e_k the dof axes at zero angles),
// is at least 30 mm per radian. A knee hinge keeps its shin marker when the foot and ankle
// markers are hidden: counting markers alone carried it (CMU 02_01: along two stance poses
// while the shin marker showed mid-swing flexion 0.75 rad away; the re-solve pulled toward
// that pose settled in a second basin, the foot's markers 250-300 mm off).
// Observers of a child are observers of its parent, so a parent's runs lie inside its
// children's (but for a child its own markers fix), and carrying each joint's local
// rotation over its own runs moves the whole unobserved part of a limb.
//
// Carry of a run with solved poses on both sides (frames a = s - 1 and b = e + 1): with
// q_a, q_b the joint's local rotations (sign-continuous), n = b - a, the log of the
// relative rotation r = log(q_a^-1 q_b), and the local angular velocities (radians per
// frame) w_a = log(q_(a-d)^-1 q_a) / d, w_b = log(q_b^-1 q_(b+d)) / d (d up to
// velocity_frames, over observed frames; 0 where there are none), frame a + t n takes
//   q(t) = q_a exp(h01(t) r + n (h10(t) w_a + h11(t) w_b)),
// the cubic Hermite basis h (h01(0) = 0, h01(1) = 1; h10, h11 the tangent terms), so the
// path meets both solved poses with matched velocities (exact at the ends; the tangent
// at b is exact to first order in |r|). An animated translation (the root's) gets the same
// cubic Hermite in R^3. A run touching the take's first or last frame holds the pose of
// its one solved side.
#ifndef MOCAPSOLVE_SIGNAL_JOINT_GAP_CARRY_H_
#define MOCAPSOLVE_SIGNAL_JOINT_GAP_CARRY_H_

#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "signal/joint_gap_template.h"

namespace mocapsolve {

struct CarriedJointRun {
  int joint = 0;
  int first = 0, last = 0;  // Frames, inclusive.
};

// Every run of every observed joint, ordered by joint then frame. `observed` holds the
// marker set's markers (same order); a sample counts when valid. Runs shorter than
// min_frames are left out.
std::vector<CarriedJointRun> FindUnobservedJointRuns(const Skeleton& skeleton, const MarkerSet& markers,
                                                     const MarkerTrajectories& observed, int min_frames = 1);

// Rewrites the local rotations (and animated translations) of *motion over the runs, as
// above. velocity_frames >= 1. Runs must fit the motion (CHECKed: programmer error).
void CarryJoints(const Skeleton& skeleton, const std::vector<CarriedJointRun>& runs, int velocity_frames,
                 Motion* motion);
// The same, but a run whose joint has no animated translation follows a template from the
// take where one matches (signal/joint_gap_template.h), the Hermite above where none does.
void CarryJoints(const Skeleton& skeleton, const std::vector<CarriedJointRun>& runs, int velocity_frames,
                 const JointTemplateOptions* templates, Motion* motion);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_JOINT_GAP_CARRY_H_
