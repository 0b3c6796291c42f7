// SkinnedMesh: an immutable linear-blend-skinned mesh bound to a Skeleton (thesis 2.4).
//
// Shapes: #V rest positions and rest normals (bind space, skeleton file units), sparse
// weights in compressed rows (vertex i's influences are [weight_begin(i),
// weight_begin(i+1)) of joints/weights), and #J joint_from_bind transforms (the inverse
// bind matrices: world_from_joint at bind time, inverted).
//
// Skinning matrix of joint b at a pose: S_b = world_from_joint_b * joint_from_bind_b.
//   position  v_i = sum_b w_ib S_b v0_i                         (eq. 5)
//   normal    n_i = sum_b w_ib rot(S_b) n0_i, not renormalized  (eq. 6; see skinning.h)
// Cumulative weight (thesis 4.3.5): w^_ij = sum of w_ib over b in subtree(j).
#ifndef MOCAPSOLVE_KINEMATICS_SKINNED_MESH_H_
#define MOCAPSOLVE_KINEMATICS_SKINNED_MESH_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct SkinInfluence {
  int joint;
  double weight;
};

struct SkinnedMeshSpec {
  Eigen::Matrix3Xd rest_positions;                 // 3 x #V, bind space.
  Eigen::Matrix3Xd rest_normals;                   // 3 x #V unit normals, or 3 x 0.
  Eigen::Matrix2Xd texcoords;                      // 2 x #V texture coordinates (glTF's u, v), or 2 x 0.
  std::vector<std::vector<SkinInfluence>> influences;  // #V lists.
  std::vector<Eigen::Isometry3d> joint_from_bind;  // #J inverse bind transforms.
};

class SkinnedMesh {
 public:
  SkinnedMesh() = default;
  // Validates sizes, joint indices, finite non-negative weights; weights of each vertex
  // are renormalized to sum 1 (a vertex with no weight is an error).
  static Status Create(const Skeleton& skeleton, SkinnedMeshSpec spec, SkinnedMesh* mesh);

  int num_vertices() const { return static_cast<int>(rest_positions_.cols()); }
  int num_joints() const { return static_cast<int>(joint_from_bind_.size()); }
  bool has_normals() const { return rest_normals_.cols() == rest_positions_.cols(); }
  bool has_texcoords() const { return num_vertices() > 0 && texcoords_.cols() == rest_positions_.cols(); }
  const Eigen::Matrix2Xd& texcoords() const { return texcoords_; }  // Only carried (skinning ignores them).
  const Eigen::Matrix3Xd& rest_positions() const { return rest_positions_; }
  const Eigen::Matrix3Xd& rest_normals() const { return rest_normals_; }
  int weight_begin(int vertex) const { return row_begin_[vertex]; }
  int weight_end(int vertex) const { return row_begin_[vertex + 1]; }
  int weight_joint(int k) const { return joints_[k]; }
  double weight(int k) const { return weights_[k]; }
  const Eigen::Isometry3d& joint_from_bind(int j) const { return joint_from_bind_[j]; }

  // Sum of vertex i's weights on joints in subtree(j) (thesis 4.3.5).
  double CumulativeWeight(const Skeleton& skeleton, int vertex, int joint) const;

 private:
  Eigen::Matrix3Xd rest_positions_;
  Eigen::Matrix3Xd rest_normals_;
  Eigen::Matrix2Xd texcoords_;
  std::vector<int> row_begin_;
  std::vector<int> joints_;
  std::vector<double> weights_;
  std::vector<Eigen::Isometry3d> joint_from_bind_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_SKINNED_MESH_H_
