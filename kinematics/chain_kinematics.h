// Forward kinematics of one joint chain read from solver parameter blocks: the first half
// of every residual over (root translation, local rotations of a chain), e.g. a marker
// (problems/marker_solve/marker_residual.h) or a tracked vertex (problems/retarget/).
//
// A chain is a set of joints sorted ascending (parents first) that starts at the root
// (joint 0) and holds every ancestor of its joints. Parameter blocks: parameters[0] the
// root translation (3, skeleton units), parameters[1 + s] the local rotation of
// joints[s] as a quaternion (x, y, z, w), normalized before use. Joints off the chain are
// not needed: a chain joint's parent is on the chain, and its translation is its offset.
//
//   R_s = R_parent(s) * R_rest_j * q_s,   o_s = o_parent(s) + R_parent(s) * offset_j
// (the root: R_0 = R_rest_0 * q_0, o_0 = parameters[0]).
#ifndef MOCAPSOLVE_KINEMATICS_CHAIN_KINEMATICS_H_
#define MOCAPSOLVE_KINEMATICS_CHAIN_KINEMATICS_H_

#include <algorithm>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/skeleton.h"

namespace mocapsolve {

struct JointChain {
  std::vector<int> joints;       // Ascending, joints[0] == 0.
  std::vector<int> parent_slot;  // Slot of each joint's parent (-1 for the root).

  JointChain() = default;
  JointChain(const Skeleton& skeleton, std::vector<int> chain_joints) : joints(std::move(chain_joints)) {
    for (int j : joints) parent_slot.push_back(skeleton.parent(j) < 0 ? -1 : slot(skeleton.parent(j)));
  }
  int size() const { return static_cast<int>(joints.size()); }
  // The slot of a joint on the chain (it must be on it).
  int slot(int joint) const {
    return static_cast<int>(std::lower_bound(joints.begin(), joints.end(), joint) - joints.begin());
  }
};

// World rotations and positions of the chain's joints (arrays of chain.size()). Returns
// false if a quaternion block is zero (the residual is then undefined).
inline bool ChainForwardKinematics(const Skeleton& skeleton, const JointChain& chain,
                                   double const* const* parameters, Eigen::Matrix3d* rotations,
                                   Eigen::Vector3d* positions) {
  for (int s = 0; s < chain.size(); ++s) {
    const int j = chain.joints[s];
    Eigen::Quaterniond local = Eigen::Map<const Eigen::Quaterniond>(parameters[1 + s]);
    const double norm = local.norm();
    if (!(norm > 0.0)) return false;
    local.coeffs() /= norm;
    if (skeleton.has_rest_rotation(j)) local = skeleton.rest_rotation(j) * local;
    const int p = chain.parent_slot[s];
    if (p < 0) {
      positions[s] = Eigen::Map<const Eigen::Vector3d>(parameters[0]);
      rotations[s] = local.toRotationMatrix();
    } else {
      positions[s] = positions[p] + rotations[p] * skeleton.offset(j);
      rotations[s] = rotations[p] * local.toRotationMatrix();
    }
  }
  return true;
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_CHAIN_KINEMATICS_H_
