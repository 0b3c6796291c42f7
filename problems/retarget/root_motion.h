// Game-engine root conventions for a retargeted clip (RetargetMotionOntoCharacter's last
// step; `--root_motion=keep|root_bone|in_place`). No minimization: a per-frame change of
// the skeleton's root that leaves every other joint where it was in the world (root_bone)
// or shifted by the removed horizontal track (in_place).
//
// The track. With p_f the hips' world position at frame f (Y up) and Q_f their world
// rotation, Q_0 the rest one: the ground projection g_f = (p_f.x, 0, p_f.z) and the
// heading h_f = the twist about +y of Q_f Q_0^-1 (swing-twist: 2 atan2(q.y, q.w)),
// unwrapped over the clip. Both are smoothed by a Gaussian of standard deviation
// `smoothing_seconds` (the hips' sway at the step frequency, ~2 Hz, removed; a straight
// walk's track is a line, kept a line at the clip's ends by point-reflecting the series
// about its first and last samples).
//
// keep: the motion as solved.
// root_bone: the skeleton's root joint (a root bone at the floor above the hips, as in
//   Unreal's and many Blender game rigs) carries the horizontal motion: its world position
//   becomes (g_f.x, y_rest, g_f.z) (y_rest: its rest height) and its world rotation
//   Ry(h_f) W_rest (W_rest: its rest world rotation, so the local rotation is
//   R_rest^-1 Ry(h_f) R_rest). Every child c of the root keeps its world frame:
//       t_c' = W'^-1 (P + W t_c - P'),   R_c' = R_rest_c^-1 W'^-1 W R_rest_c R_c
//   (P, W the root's old world position and rotation, P', W' the new ones), so all other
//   joints' world positions and rotations are unchanged (to rounding): foot plants and
//   floor clearance are those of keep. A skeleton whose root is the hips has no root
//   bone: an error naming the hips.
// in_place: the horizontal track removed: every joint's world position shifted by
//   -(g_f - g_0) (the clip stays where it began; the heading, the hips' sway and the
//   vertical motion are kept). With a root bone above the hips, it then stays at its rest
//   transform (its children keep their shifted world frames), so the engine's root is
//   still. Planted feet are planted in the frame that moves with the removed track.
//
// Stride: the solve (retarget_clip.h) already scales the source's root translation by the
// height ratio and the foot plants hold the feet where contacts began; this step adds no
// skating in any mode (root_bone: no joint below the root moves in the world; in_place: a
// rigid horizontal shift per frame, which the track's frame undoes).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_ROOT_MOTION_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_ROOT_MOTION_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

enum class RootMotionMode { kKeep, kRootBone, kInPlace };

// "keep", "root_bone", "in_place".
bool ParseRootMotionMode(const std::string& text, RootMotionMode* mode);
const char* RootMotionModeName(RootMotionMode mode);

struct RootMotionOptions {
  RootMotionMode mode = RootMotionMode::kKeep;
  double smoothing_seconds = 0.15;  // Gaussian standard deviation of the track; 0 = none.
};

struct RootMotionResult {
  int hips = -1;        // The joint whose ground projection is the track.
  int root_bone = -1;   // root_bone / in_place on a rig with a root above the hips: joint 0.
  std::vector<Eigen::Vector3d> track;  // g_f, smoothed (world, y = 0).
  std::vector<double> heading;         // h_f, smoothed, unwrapped (radians).
  double track_length = 0.0;           // Summed horizontal distance of the track.
  std::string note;                    // One line for the report.
};

// The hips of a skeleton that has no humanoid roles: the first joint from the root at
// which two chains branch (children without children of their own, such as IK targets
// under a root bone, do not count), following the one chain until then.
int FirstBranchingJoint(const Skeleton& skeleton);

// Applies `options.mode` to `motion` (on `skeleton`), `hips` the joint the track follows.
// Errors: root_bone on a skeleton whose root is `hips`; a motion without a frame rate
// when smoothing is asked.
Status ApplyRootMotion(const Skeleton& skeleton, int hips, const RootMotionOptions& options, Motion* motion,
                       RootMotionResult* result);

// The smoothed track and heading of `hips` over `motion` (the first part of ApplyRootMotion).
void MeasureRootTrack(const Skeleton& skeleton, int hips, const Motion& motion, double smoothing_seconds,
                      RootMotionResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_ROOT_MOTION_H_
