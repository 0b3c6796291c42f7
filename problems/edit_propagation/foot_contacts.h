// Foot contacts and keeping them through an edit: the paper's stated limit ("editing a
// foot that is planted on the ground will produce the infamous skating foot if not
// treated as a constrained problem", Dean et al. 2018, section 4), treated as one.
//
// Detection (on the source motion). For each foot joint k (auto: every joint whose name
// contains "foot", "toe" or "ankle", case-insensitive) with world position p_k(f)
// (forward_kinematics.h, skeleton units), frame f is a contact when
//   p_k(f)[up] - min_f' p_k(f')[up] <= height_threshold      (skeleton units), and
//   |p_k(f + 1) - p_k(f - 1)| / (2 dt) <= speed_threshold    (skeleton units per second;
//                                                             one-sided at the clip ends).
// The floor is each joint's own lowest height in the clip, so a flat floor is assumed.
// Per joint, gaps of at most max_gap_seconds between contact frames are then closed and
// contact runs shorter than min_contact_seconds dropped (the thresholds flicker otherwise).
//
// Keeping them (after propagation). Every frame with at least one contact is re-solved
// with the marker-solving residuals (problems/marker_solve/): each contact joint is a
// marker at zero offset on that joint, observed at its source position p_k(f):
//
//   minimize  sum_{k in contact at f} |contact_weight (x_k(q) - p_k(f))|^2     (MarkerResidual)
//           + sum_{j free} |2 prior_weight (q_j - s q_j^prop)|^2     (RotationPriorResidual)
//
// over the local rotations q_j of the joints on the contact joints' chains (each on its
// dof manifold), with the root (translation and rotation) held at the propagated pose by
// default, so a pelvis or root edit is kept and the legs absorb it. q^prop is the
// propagated pose, or, for a joint also solved at the previous frame, the propagated pose
// with the previous frame's correction applied (so the correction carries on smoothly when
// the set of planted joints changes, e.g. heel-off with the toes still down); prior_weight
// is in skeleton units of foot error per radian.
//
// Blending. A joint is re-solved only at frames where a foot on its chain is planted, so
// its correction c_j(f) = log(q_j^prop(f)^-1 q_j(f)) would switch on and off abruptly (a
// 30 degree pop of the legs on 16_15). Between solved frames a < f < b (per joint) the
// correction is interpolated and eased out: c_j(f) = e(f) ((1 - t) c_j(a) + t c_j(b)),
// t = (f - a)/(b - a), e(f) = max(h((f - a)/W), h((b - f)/W)), h(s) = 1 - 3 s^2 + 2 s^3
// (0 for s >= 1), W = blend_seconds * frame rate; one-sided at the clip's ends.
#ifndef MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_FOOT_CONTACTS_H_
#define MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_FOOT_CONTACTS_H_

#include <functional>
#include <string>
#include <vector>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

// Joints whose names contain "foot", "toe" or "ankle" (case-insensitive), ascending.
std::vector<int> AutoFootJoints(const Skeleton& skeleton);

struct FootContactOptions {
  std::vector<int> joints;        // Foot joints; empty = AutoFootJoints.
  double height_threshold = 0.0;  // Skeleton units above the joint's lowest point (> 0).
  double speed_threshold = 0.0;   // Skeleton units per second (> 0).
  int up_axis = 1;                // 0 = x, 1 = y (BVH, ASF), 2 = z.
  double max_gap_seconds = 0.05;      // Gaps this short between contacts are closed.
  double min_contact_seconds = 0.05;  // Then contact runs shorter than this are dropped.
};

struct FootContacts {
  std::vector<int> joints;                       // Foot joints.
  std::vector<std::vector<char>> in_contact;     // [k][f]: joint k planted at frame f.
  std::vector<Vector3dVector> positions;         // [k][f]: source world positions.
  int num_frames() const { return joints.empty() ? 0 : static_cast<int>(in_contact[0].size()); }
  int ContactSamples() const;                    // Number of (k, f) in contact.
  int ContactFrames() const;                     // Frames with any contact.
};

// Errors: no foot joints (message suggests --foot_joints), bad thresholds, a motion
// without a frame rate or not fitting the skeleton.
Status DetectFootContacts(const Skeleton& skeleton, const Motion& motion,
                          const FootContactOptions& options, FootContacts* contacts);

// max over contact samples of |p_k(f) in `motion` - contacts.positions[k][f]| (skeleton
// units); 0 without contacts.
double MaxContactDrift(const Skeleton& skeleton, const FootContacts& contacts, const Motion& motion);

struct ContactSolveOptions {
  double contact_weight = 1.0;  // Per skeleton unit of foot error.
  double prior_weight = 1.0;    // Skeleton units of foot error per radian of rotation change.
  bool fix_root = true;         // Hold the root's translation and rotation.
  // Each joint's correction is eased into the frames around its solved frames over this
  // time (see KeepContacts); 0 = off (legs then pop where contacts begin and end).
  double blend_seconds = 0.2;
  int max_iterations = 50;
  bool IsValid(std::string* error) const;
};

struct ContactSolveReport {
  int frames_solved = 0;
  int contact_samples = 0;
  int failed_frames = 0;          // Solver not usable: the propagated pose was kept.
  double max_drift_before = 0.0;  // Skeleton units.
  double max_drift_after = 0.0;
  double solve_seconds = 0.0;
};

// Re-solves the contact frames of *motion (the propagated clip) in place. progress
// (optional): frames scanned so far, of motion's frames.
Status KeepContacts(const Skeleton& skeleton, const FootContacts& contacts,
                    const ContactSolveOptions& options, Motion* motion, ContactSolveReport* report,
                    const std::function<void(int frames_done)>& progress = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_EDIT_PROPAGATION_FOOT_CONTACTS_H_
