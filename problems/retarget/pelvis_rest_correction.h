// PelvisRestCorrection: the rest-pose alignment's rotation for the root-most mapped joint
// (the pelvis), skeleton_binding.h step 3, and the same rule wherever a rest correspondence
// of the pelvis is needed (retarget_quality.h's torso orientation).
//
// Inputs: unit vectors u_c (the source pelvis's mapped children, where they start from it,
// in the Y-up world) and v_c (the target's, bind pose, same world), c = 1..n.
//
// Where a rig's pelvis children start (hips, spine) is partly its design: RobotExpressive's
// Body -> Abdomen leans 40 degrees back, CMU's root -> lowerback is straight up. A full
// Kabsch rotation E = argmin_R sum |R u_c - v_c|^2 turns the source pelvis by the
// difference of the designs, and whatever rides on the pelvis (a torso mesh bound to it)
// stays tilted by as much through the take. The heading (a turn about +y) is never a
// matter of design: both rest poses stand upright, the facing differs.
//
//   Y      = the turn about +y that best turns the horizontal parts of the u_c onto the
//            v_c's: theta = atan2(sum (u_c x v_c).y, sum u_c.v_c), horizontal parts only;
//   E      = Kabsch (the minimal rotation of the means when the u_c are (nearly)
//            parallel, or n = 1);
//   r      = the fit's residual, sqrt(mean_c angle(E u_c, v_c)^2) (degrees): 0 when the two
//            sets of children are one set turned (the same rig; a rig whose rest pose is
//            not its bind pose), large when the designs differ;
//   w      = 1 for r <= kPelvisAgreeDeg, 0 for r >= kPelvisDisagreeDeg, linear between, and
//            0 for n < 3;
//   result = slerp(Y, E, w): the tilt is kept only as far as both rigs' children agree.
//
// Fewer than three children count as disagreeing (Y only): two mirror children (the thighs,
// CMU's root) fit any tilt about the axis between them exactly, so their fit says nothing
// about a tilt. kPelvisAgreeDeg = 1, kPelvisDisagreeDeg = 3: the shared characters' own BVH exports give
// r <= 0.0001; other rigs 4.7-38 (BENCHMARKS.md, issue 29). Y is the identity when the
// horizontal parts sum to nothing (every child straight up or down). skeleton_binding.cc
// stands the pelvis up (the whole body's axis) before this.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_PELVIS_REST_CORRECTION_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_PELVIS_REST_CORRECTION_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mocapsolve {

constexpr double kPelvisAgreeDeg = 1.0;
constexpr double kPelvisDisagreeDeg = 3.0;

// argmin_R sum |R u_i - v_i|^2 over unit vectors (Kabsch), or the minimal rotation taking
// the mean u to the mean v when the u are (nearly) parallel (second singular value below
// 0.05 of the first) or there is one: the rotation about them is not determined (CMU's
// thorax, whose neck and both clavicles start at one point) and the minimal one keeps the
// source's.
Eigen::Quaterniond BestRestRotation(const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& v);

// Y above: the best turn about +y.
Eigen::Quaterniond BestTurnAboutUp(const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& v);

struct PelvisCorrection {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // slerp(Y, E, w).
  double residual_deg = 0.0;  // r.
  double tilt_kept = 0.0;     // w.
};

// Empty u: identity.
PelvisCorrection PelvisRestCorrection(const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& v);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_PELVIS_REST_CORRECTION_H_
