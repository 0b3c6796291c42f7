// Pose edits and their propagation through a clip (Dean, Lewis & Chalmers 2018, eqs. 4-5).
//
// An edit replaces the pose p_i of one frame i by an edited pose p'_i. Per joint j, in
// the log map of the joint's local rotation (a rotation vector, radians):
//
//   delta_j = log(p'_ij) - log(p_ij)                                         (eq. 4)
//   p'_fj   = exp(log(p_fj) + sum_k w_k(f) delta_kj)    for every frame f    (eq. 5)
//
// with w_k(f) in [0, 1] the falloff weight of edit k at frame f (1 at its own frame for a
// single edit; Green's, harmonic or spline falloffs, see falloff.h / harmonic_falloff.h /
// spline_falloff.h). Translations (the root's position, and any joint with translation
// channels) are edited linearly: t'_fj = t_fj + sum_k w_k(f) (t'_ij - t_ij), skeleton units.
//
// Sign continuity. q and -q are one rotation, but log is additive only within one chart.
// Each joint's rotation series is made sign-continuous over the clip (MakeSignContinuous),
// flipped as a whole so that its mean w is >= 0, and its logs are the unfolded logs
// UnfoldedLog(q) = 2 atan2(|v|, w) v / |v| (angle in [0, 2 pi), no hemisphere fold), which
// are continuous along a sign-continuous series, also where the rotation passes through pi
// (LogMap would jump there from +pi to -pi). The edited rotation p'_ij takes the sign
// nearest the series' q at frame i. Since ExpMap(UnfoldedLog(q)) = q exactly, a single edit
// with w = 1 at its frame reproduces the edited pose exactly and w = 0 leaves a frame as it
// was (up to round-off, sign aside).
//
// Several edits at once: weights[k] is edit k's field; at an edited frame the sum gives
// that edit's delta exactly only when the other fields vanish there (the harmonic fields
// do by construction: u_k = 0 at the other edited frames).
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_POSE_EDIT_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_POSE_EDIT_H_

#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

// One edited frame: its index and the whole edited pose (sizes of the skeleton).
struct PoseEdit {
  int frame = -1;
  Pose edited;
};

// Rotation offsets (local increments, R'_j = R_j exp(offset_j), radians, in joint j's
// frame) and a root translation offset (skeleton units, world frame) at one frame.
struct PoseOffsets {
  int frame = -1;
  std::vector<std::pair<int, Eigen::Vector3d>> rotation_offsets;  // (joint, rotation vector).
  Eigen::Vector3d root_translation_offset = Eigen::Vector3d::Zero();
};

// The unfolded log map: rotation vector of angle 2 atan2(|v|, w) in [0, 2 pi) about v / |v|
// (Taylor branch near 0; at q = -1 exactly, where the axis is undefined, LogMap(-q)).
Eigen::Vector3d UnfoldedLog(const Eigen::Quaterniond& q);

// The edit of `offsets` applied to motion.frames[offsets.frame]. Errors: frame out of
// range, joint out of range, non-finite offsets.
Status MakeEdit(const Motion& motion, const PoseOffsets& offsets, PoseEdit* edit);

// Per-joint log deltas (eq. 4) of each edit against the sign-continuous series of
// `motion` (see above): deltas[j], radians; translation_deltas[j], skeleton units.
struct EditDeltas {
  std::vector<Eigen::Vector3d> rotation;
  std::vector<Eigen::Vector3d> translation;
};

// Applies eq. 5: weights[k] (size #frames, finite) is edit k's falloff. *out may alias
// nothing of `motion`. Errors: size mismatches, an edit frame out of range, two edits of one
// frame, non-finite weights.
Status PropagateEdits(const Skeleton& skeleton, const Motion& motion,
                      const std::vector<PoseEdit>& edits,
                      const std::vector<Eigen::VectorXd>& weights, Motion* out,
                      std::vector<EditDeltas>* deltas = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_POSE_EDIT_H_
