// Vertex subsampling for mesh retargeting (thesis 4.3.1, Algorithm 5).
//
// Input: the mesh's vertex positions P (3 x #V) and unit normals N (3 x #V) in one pose
// (the rest pose), and its skin weights. Output: the indices S of about #V / ratio
// vertices, in the order they were picked.
//
//   1. Normal check: a vertex is eligible only if its normal agrees with the average of its
//      `neighbours` nearest vertices' normals (kd-tree, nanoflann):
//        1 - n_i . normalize(sum_k n_k) <= normal_threshold   (0.05, thesis; ~18 degrees)
//      (holes, extrusions and hard edges have normals unlike their neighbours').
//   2. Farthest-point sampling over the eligible vertices, from vertex `first` (or the
//      first eligible one): S_k = argmax_i min_{s in S} |P_i - P_s|^2, until #V / ratio
//      samples (at least 1).
//   3. Per joint: every joint that dominates (largest skin weight) some vertex gets at
//      least min_per_joint samples among the vertices it dominates, added by the same
//      farthest-point rule restricted to them (eligible ones first; if the joint has too
//      few eligible vertices, its ineligible ones too), so that each joint can be placed.
//   4. Per body part (when `parts` is given: per vertex, a part index or -1): every part
//      with vertices gets at least min_per_part samples by the same rule. A part is a role
//      of humanoid_roles.h with the joints below it (BodyParts), so a limb made of several
//      small rigid meshes (RobotExpressive's arm: no vertex of the forearm, a hand of 60
//      vertices among 3,700) is tracked by a few vertices however sparse the whole-mesh
//      sampling is there.
// Deterministic for a given `first`.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_VERTEX_SUBSAMPLING_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_VERTEX_SUBSAMPLING_H_

#include <vector>

#include <Eigen/Core>

#include "kinematics/skinned_mesh.h"

namespace mocapsolve {

struct SubsampleOptions {
  int ratio = 128;                // #V : #samples.
  double normal_threshold = 0.05;  // On 1 - cos(angle to the neighbours' mean normal).
  int neighbours = 8;             // For the mean normal.
  int min_per_joint = 3;
  int min_per_part = 6;
  int first = 0;                  // Starting vertex of the farthest-point sampling.
};

// The joint with the largest skin weight on the vertex (lowest index on ties).
int DominantJoint(const SkinnedMesh& mesh, int vertex);

// `positions` and `normals` are 3 x mesh.num_vertices() (normals unit); `parts` empty or
// one entry per vertex; CHECKs sizes.
std::vector<int> SubsampleVertices(const SkinnedMesh& mesh, const Eigen::Matrix3Xd& positions,
                                   const Eigen::Matrix3Xd& normals,
                                   const SubsampleOptions& options, const std::vector<int>& parts = {});

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_VERTEX_SUBSAMPLING_H_
