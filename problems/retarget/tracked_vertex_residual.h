// TrackedVertexResidual: one tracked target vertex at one frame (thesis eqs. 12-17, with
// the exact derivatives of kinematics/kinematic_jacobians.h in place of eqs. 12-13).
//
//   position (B = 0):  r = (weight / sigma) (v(t_root, q) - g)          3 rows, unitless
//   normal   (B = 1):  r = weight (n(q) - m)                            3 rows, unitless
//
// with the LBS position and (not renormalized) normal of target vertex i (eqs. 5-6)
//   v = sum_b w_b (o_b + R_b z_b),   n = sum_b w_b R_b y_b,
// z_b = joint_from_bind_b v0_i and y_b = rot(joint_from_bind_b) n0_i constant, R_b and o_b
// the world rotation and origin of influencing joint b from the chain's forward kinematics,
// g / m the goal position / normal (retarget_setup.h) and sigma the clip's normalization.
// chain(i): the ancestors of the vertex's influencing joints, parents first (always
// starting at the root, joint 0).
//
// Parameter blocks, in order:
//   0:      the root translation t_root, 3 doubles (target skeleton units, world frame);
//   1 + s:  the local rotation q_j of joint j = chain(i)[s], 4 doubles in Eigen order
//           (x, y, z, w) on RightQuaternionManifold (R_j <- R_j exp(delta)).
// Non-root joints keep their skeleton offsets as translations.
//
// Jacobians (row-major; any may be null, and `jacobians` itself may be null):
//   position: d r / d t_root = (weight / sigma) I (3 x 3);
//             d r / d q_j    = (weight / sigma) sum_{b in subtree(j)} w_b [o_j - p_b]x R_j
//                              * AmbientFromTangent(q_j) / |q_j|   (3 x 4), p_b = o_b + R_b z_b;
//   normal:   d r / d t_root = 0;
//             d r / d q_j    = -weight sum_{b in subtree(j)} w_b [R_b y_b]x R_j
//                              * AmbientFromTangent(q_j) / |q_j|.
// Both are exact also when part of the vertex's weight lies outside subtree(j) (thesis
// eq. 12's w^_j (v - o_j) is not). The tangent blocks (before AmbientFromTangent) are
// what the lean DLS kernel of retarget_frame_solver.h assembles directly.
//
// The goal is read through a pointer at each Evaluate, so a solver moves one Problem
// from frame to frame by updating the goals in place.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_TRACKED_VERTEX_RESIDUAL_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_TRACKED_VERTEX_RESIDUAL_H_

#include <vector>

#include <ceres/cost_function.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/chain_kinematics.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"

namespace mocapsolve {

// chain(i): ancestors (and selves) of the vertex's influencing joints, sorted.
std::vector<int> VertexChain(const Skeleton& skeleton, const SkinnedMesh& mesh, int vertex);

class TrackedVertexResidual : public ceres::CostFunction {
 public:
  // The skeleton, mesh and goal must outlive the residual. `scale` = weight / sigma for
  // positions, weight for normals.
  TrackedVertexResidual(const Skeleton* skeleton, const SkinnedMesh* mesh, int vertex,
                        bool track_position, const Eigen::Vector3d* goal, double scale);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  const std::vector<int>& joints() const { return chain_.joints; }
  int vertex() const { return vertex_; }
  bool track_position() const { return track_position_; }
  double scale() const { return scale_; }

 private:
  const Skeleton* skeleton_;
  int vertex_;
  bool track_position_;
  const Eigen::Vector3d* goal_;
  double scale_;
  JointChain chain_;
  struct Influence {
    int slot;
    double weight;
    Eigen::Vector3d local;  // z_b (position) or y_b (normal).
  };
  std::vector<Influence> influences_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_TRACKED_VERTEX_RESIDUAL_H_
