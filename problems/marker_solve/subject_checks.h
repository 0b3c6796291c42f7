// Checks of a fitted subject (skeleton + marker set + the motion solved on them) that do
// not trust the marker residual: a low residual bought with absurd marker offsets or a
// tilted torso is a failed fit, and these measures say so.
//
//  1. Skin distance. A marker sits on the skin over its bone: its offset z (joint frame)
//     lies within `max_marker_bone_distance` of the joint's bone. The bone of joint j
//     (BoneSegments) is the set of segments from the origin of every joint rigidly
//     attached to j (j itself, and descendants reached through joints with no rotation
//     dofs, such as the ASF hip joints under the root) to each of its children's origins
//     and end sites, all in j's frame:
//       child origin in j's frame = F_k * t_c,  F_c = F_k * T(t_c) * R_rest_c (rigid c).
//     A leaf without end sites is a point (its origin). Distances are to the nearest point
//     of the nearest segment. With `held` (per joint: in a held limb, held_segments.h,
//     HeldLimbJoints), a held child c of that body is rigid with it in a fit (no marker
//     turns it; it stays at its zero rotation, F_c as above), so c's own segments (to its
//     children's origins and end sites, not their held subtrees) count as j's bone too: a
//     Davis set's acromion rides the thorax 17-20 cm from the spine, on the held clavicle's
//     bone, within the skin of the thorax's rigid body. The check uses the fitted markers'
//     held limbs.
//  2. Torso direction. Per frame, the solved pelvis-to-head direction (the head joint's
//     origin minus the root's) against the markers' own: the centroid of the observed
//     head markers minus that of the pelvis markers, chosen by label (LFHD RFHD LBHD
//     RBHD; LFWT RFWT LBWT RBWT LASI RASI LPSI RPSI, or the options' lists), so a fit that moved markers along
//     with a tilted skeleton cannot hide. Frames with fewer than 2 markers of either group
//     are skipped. The mean angle is checked; the max is reported.
//  3. Symmetry. Each left/right pair of joints (names that differ only in a leading l/r
//     or Left/Right, SideFreeName) has bone lengths |t_j| within `max_asymmetry`
//     (relative to the longer); pairs whose longer bone is under min_symmetry_bone_share of
//     the skeleton's longest bone are not compared (scale-free: fingers, whose template
//     differences of a few millimetres are large relative to them: CMU's 02.asf gives its
//     hands 0.661 and 0.730 units, so its fingers' offsets differ by 9.5 %, at 9-10 % of the
//     tibia; every other CMU pair is >= 20 % of it).
//  4. Residual. The marker RMS of the motion on the model, over every observed sample,
//     within max_rms_mm: plausible geometry that does not explain the markers also fails.
// Lengths are in skeleton units in the structs; *_cm fields convert with the skeleton's
// unit (which must be known for the centimetre thresholds).
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SUBJECT_CHECKS_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SUBJECT_CHECKS_H_

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

// "lfemur" -> "femur", "RightUpLeg" -> "upleg", "root" -> "oot" (no twin: harmless).
std::string SideFreeName(const std::string& name);
// The left/right twin of joint j (-1 if none).
int MirrorJoint(const Skeleton& skeleton, int j);

// The bone of joint j as segments (start, end) in j's frame (see the header comment);
// `held` empty: no joint held.
std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> BoneSegments(const Skeleton& skeleton, int j,
                                                                      const std::vector<bool>& held = {});
// Distance from a point in j's frame to j's bone; and the point moved onto the bone's
// tube of radius max_distance when it lies outside (unchanged otherwise).
double DistanceToBone(const Skeleton& skeleton, int j, const Eigen::Vector3d& point,
                      const std::vector<bool>& held = {});
Eigen::Vector3d ClampToBone(const Skeleton& skeleton, int j, const Eigen::Vector3d& point, double max_distance,
                            const std::vector<bool>& held = {});

struct SubjectCheckOptions {
  double max_marker_bone_distance_cm = 15.0;
  double max_torso_error_deg = 15.0;
  double max_asymmetry = 0.05;
  double min_symmetry_bone_share = 0.15;  // Of the longest bone: shorter pairs (fingers) are not compared.
  double max_rms_mm = 25.0;           // 4. The model must also explain the markers.
  // 2. The head's and the pelvis' markers by label; empty: the labels above.
  std::vector<std::string> head_labels, pelvis_labels;
};

struct MarkerDistance {
  std::string label, joint;
  double to_bone_cm = 0.0;   // Skin distance (check 1).
  double to_joint_cm = 0.0;  // To the joint's origin (informative).
};

struct SubjectChecks {
  double rms_mm = 0.0;                   // Marker RMS of the solved motion (check 4).
  int samples = 0;
  std::vector<MarkerDistance> markers;   // Per marker (its farthest attachment).
  double max_bone_distance_cm = 0.0;
  double max_joint_distance_cm = 0.0;
  std::string farthest_marker;
  int torso_frames = 0;                  // Frames the torso direction was measured in.
  double torso_error_mean_deg = 0.0, torso_error_max_deg = 0.0;
  double max_asymmetry = 0.0;            // Relative.
  std::string least_symmetric_pair;
  std::vector<std::string> failures;     // One line per failed check; empty: passed.
  bool ok() const { return failures.empty(); }
};

// observed[f][m] in skeleton units and axes (marker_observations.h); motion solved on
// the skeleton for the same frames. The skeleton's unit must be known.
SubjectChecks CheckSubjectFit(const Skeleton& skeleton, const MarkerSet& markers,
                              const std::vector<std::vector<Eigen::Vector3d>>& observed, const Motion& motion,
                              const SubjectCheckOptions& options = {});

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SUBJECT_CHECKS_H_
