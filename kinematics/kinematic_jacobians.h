// Analytic derivatives of world joint positions, blended (skinned) points and skinned
// normals with respect to the pose.
//
// Pose tangent layout (size 3 + 3 #J): [root translation (3) | delta_0 | ... | delta_{J-1}],
// where a solver updates R_j <- R_j * exp(delta_j), delta_j in joint j's local frame
// (after its rest rotation). Jacobians are 3 x (3 + 3 #J), written into a caller-sized
// matrix that is zeroed first; only the blocks of ancestors of the influencing joints
// are non-zero.
//
// Blended point x = sum_b w_b p_b, with p_b rigidly attached to joint b (a marker on
// several bones, eq. 9, or an LBS vertex, eq. 5 with p_b = S_b v0). Rotating joint j by
// delta about its world axes a_k = world_rotation_j e_k, centred at o_j, moves every p_b
// with b in subtree(j):
//   dx/d delta_jk = a_k x (sum_{b in subtree(j)} w_b p_b - w^_j o_j),  w^_j = cumulative
// weight; in block form  dx/d delta_j = sum_{b in subtree(j)} w_b [o_j - p_b]x R_j.
// Thesis eq. 12 writes w^_j (x - o_j) instead, which is exact only when all of the
// point's weight lies in subtree(j) (DESIGN.md). dx/d root translation = (sum_b w_b) I.
// A skinned normal n = sum_b w_b rot(S_b) n0 has dn/d delta_j = -sum_{b in subtree(j)}
// w_b [n_b]x R_j (eq. 13 likewise exact only for w^_j = 1) and no translation part.
#ifndef MOCAPSOLVE_KINEMATICS_KINEMATIC_JACOBIANS_H_
#define MOCAPSOLVE_KINEMATICS_KINEMATIC_JACOBIANS_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/forward_kinematics.h"
#include "kinematics/skinned_mesh.h"

namespace mocapsolve {

using PoseJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic>;

inline int PoseTangentSize(const Skeleton& skeleton) { return 3 + 3 * skeleton.num_joints(); }
inline int RotationColumn(int joint) { return 3 + 3 * joint; }

// One rigid attachment of a blended point: world point p_b on joint b, weight w_b.
struct BlendTerm {
  int joint;
  double weight;
  Eigen::Vector3d point_in_world;
};

// d(sum_b w_b p_b)/d pose, added to *jacobian (not zeroed; sized 3 x PoseTangentSize).
void AccumulateBlendedPointJacobian(const Skeleton& skeleton, const FkData& fk,
                                    const std::vector<BlendTerm>& terms,
                                    PoseJacobian* jacobian);

// d(world position of joint)/d pose.
void JointPositionJacobian(const Skeleton& skeleton, const FkData& fk, int joint,
                           PoseJacobian* jacobian);

// d(skinned position / normal of vertex)/d pose; `transforms` from
// ComputeSkinningTransforms at the same pose.
void SkinnedPositionJacobian(const Skeleton& skeleton, const SkinnedMesh& mesh,
                             const FkData& fk, const std::vector<Eigen::Isometry3d>& transforms,
                             int vertex, PoseJacobian* jacobian);
void SkinnedNormalJacobian(const Skeleton& skeleton, const SkinnedMesh& mesh, const FkData& fk,
                           const std::vector<Eigen::Isometry3d>& transforms, int vertex,
                           PoseJacobian* jacobian);

// The retraction the derivatives above refer to: translation += d[0:3],
// R_j <- R_j exp(d[3+3j : 6+3j]).
void RetractPose(const Eigen::VectorXd& tangent, Pose* pose);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_KINEMATIC_JACOBIANS_H_
