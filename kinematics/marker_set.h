// MarkerSet: how optical markers ride on a skeleton (thesis eq. 9).
//
// Marker m is a blend of points rigidly attached to joints:
//   x_m = sum_k w_mk * world_from_joint_{j_mk} * z_mk
// with z_mk the marker's offset in joint j_mk's frame (skeleton length units) and weights
// w_mk >= 0 summing to 1. A marker on one bone has a single attachment with weight 1.
// Labels are matched against marker files with MarkerTrajectories::FindMarker, which
// ignores subject prefixes ("LBWT" finds "TakeoMonday:LBWT").
#ifndef MOCAPSOLVE_KINEMATICS_MARKER_SET_H_
#define MOCAPSOLVE_KINEMATICS_MARKER_SET_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/forward_kinematics.h"
#include "kinematics/kinematic_jacobians.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct MarkerAttachment {
  int joint = -1;
  double weight = 1.0;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // In the joint's frame.
};

struct MarkerSpec {
  std::string label;
  std::vector<MarkerAttachment> attachments;
  // Relative weight of the marker's residual in a solve (a per-marker tolerance: 1/sigma^2
  // of its soft-tissue spread relative to the set's typical one, learned on a calibration
  // take, problems/marker_solve/marker_weights.h); the solvers scale its rows by
  // sqrt(solve_weight). Finite, in (0, 1e6]; 1 = as every other marker.
  double solve_weight = 1.0;
};

class MarkerSet {
 public:
  MarkerSet() = default;
  // Validates joints against the skeleton, finite offsets, non-negative weights with a
  // positive sum (renormalized to 1), unique non-empty labels.
  static Status Create(const Skeleton& skeleton, std::vector<MarkerSpec> markers,
                       MarkerSet* marker_set);

  int num_markers() const { return static_cast<int>(markers_.size()); }
  const MarkerSpec& marker(int m) const { return markers_[m]; }
  const std::string& label(int m) const { return markers_[m].label; }
  int FindMarker(const std::string& label) const;  // -1 if absent.

  // World position of marker m at the pose whose FK is `fk`.
  Eigen::Vector3d Position(int m, const FkData& fk) const;
  // The blend terms of marker m for AccumulateBlendedPointJacobian.
  void BlendTerms(int m, const FkData& fk, std::vector<BlendTerm>* terms) const;
  // Joints whose rotation moves marker m: the union of its attachments' ancestor chains,
  // sorted ascending (parents first).
  const std::vector<int>& InfluencingJoints(int m) const { return influencing_joints_[m]; }

 private:
  std::vector<MarkerSpec> markers_;
  std::vector<std::vector<int>> influencing_joints_;
};

// FK's companion for whole-set solvers and benchmarks: the dense Jacobian of every marker
// position, 3 #markers x PoseTangentSize (pose tangent layout of kinematic_jacobians.h;
// rows 3m..3m+2 are marker m), at the pose whose FK is `fk`. The matrix is resized and
// zeroed, then each attachment's blocks w I (translation) and w [o_j - p]x R_j (joint j on
// its chain) are added, the formula of AccumulateBlendedPointJacobian written straight
// into the big matrix. `rotations` is scratch (each joint's rotation matrix, once).
void MarkerSetJacobian(const Skeleton& skeleton, const MarkerSet& markers, const FkData& fk,
                       std::vector<Eigen::Matrix3d>* rotations, Eigen::MatrixXd* jacobian);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_MARKER_SET_H_
