// A template for a joint carried across a gap: the same joint's solved motion elsewhere in
// the take (one stride earlier or later in a walk, the same move repeated), found where the
// joints the markers still see moved as they do around the gap.
//
// For a run [s, e] of joint j (edges a = s - 1, b = e + 1, n = b - a) and a shift tau, the
// match cost is the mean squared angle between the local rotations q_k(f) and q_k(f + tau)
// over the frames f of [a - margin, b + margin], for every joint k but the root with rotation
// dofs that is observed (in no run) at both f and f + tau, and for j itself at the frames
// of the margins where it is observed at both. A shift qualifies when the source frames
// [a + tau, b + tau] lie inside the take with j observed over all of them, and at least
// half of the pairs the window holds are counted. The best qualifying shift whose root
// mean squared angle is below max_rms_angle is returned; 0 when none. Only shifts with
// |tau| <= max_shift_frames are searched: each run costs time in proportion to the shifts
// searched, so an unbounded search over a take of F frames with runs throughout costs F^2
// (CMU 02_05 looped to 29,664 frames: 633 s in this search; an hour at 120 Hz: days). A
// take no longer than the bound is searched whole, as it was before the bound.
//
// The carried rotation then follows the template, bent to meet both solved edges:
//   q(f) = q_j(f + tau) exp((1 - h(t)) d_a + h(t) d_b),  t = (f - a) / n,
//   d_a = log(q_j(a + tau)^-1 q_j(a)),  d_b = log(q_j(b + tau)^-1 q_j(b)),
// h(t) = 3t^2 - 2t^3 (so the template's own velocity is kept at both edges).
#ifndef MOCAPSOLVE_SIGNAL_JOINT_GAP_TEMPLATE_H_
#define MOCAPSOLVE_SIGNAL_JOINT_GAP_TEMPLATE_H_

#include <vector>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"

namespace mocapsolve {

struct CarriedJointRun;

struct JointTemplateOptions {
  int margin = 20;              // Frames each side of the run compared.
  double max_rms_angle = 0.15;  // Radians: the worst match accepted.
  int max_shift_frames = 3600;  // The farthest template searched, either side (30 s at 120 Hz); <= 0: any.
};

// What the search's cheap bound reads, laid out for it: per frame of [first, last], the
// unit local rotation of every joint but the root with rotation dofs, and whether it is
// carried, frame-major (the motion's poses and `carried` are joint-major, a pointer apiece).
// Made once for every run of a take (CarryJoints): the search reads only samples that are
// not carried, and carrying a run writes only carried samples, so the table stays the
// motion's wherever it is read, as long as `carried` is the one it was made from.
class JointTemplateTable {
 public:
  JointTemplateTable(const Skeleton& skeleton, const Motion& motion, const std::vector<std::vector<char>>& carried,
                     int first, int last);
  int first() const { return first_; }
  int last() const { return first_ + frames_ - 1; }
  const std::vector<int>& joints() const { return joints_; }  // The joints, ascending.
  const double* unit(int frame) const { return unit_.data() + 4 * joints_.size() * (frame - first_); }
  const char* carried(int frame) const { return carried_.data() + joints_.size() * (frame - first_); }

 private:
  int first_, frames_;
  std::vector<int> joints_;
  std::vector<double> unit_;   // 4 per joint per frame (x y z w).
  std::vector<char> carried_;  // 1 per joint per frame.
};

// carried[j][f]: joint j is in one of its runs at frame f (joints x frames).
int FindTemplateShift(const Skeleton& skeleton, const Motion& motion, const std::vector<std::vector<char>>& carried,
                      const CarriedJointRun& run, const JointTemplateOptions& options);
// The same with a table made from this motion and `carried` (see above) over at least the
// frames the run's shifts reach; the same shift.
int FindTemplateShift(const Skeleton& skeleton, const Motion& motion, const std::vector<std::vector<char>>& carried,
                      const JointTemplateTable& table, const CarriedJointRun& run, const JointTemplateOptions& options);

// Writes the run's rotations of *motion from the template at shift tau (see above). The
// run has solved poses on both sides and its source frames lie inside the take.
void CarryFromTemplate(const CarriedJointRun& run, int tau, Motion* motion);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_JOINT_GAP_TEMPLATE_H_
