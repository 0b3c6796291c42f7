// Linear blend skinning of points and normals (thesis eqs. 5 and 6).
//
// Normals follow eq. 6 literally: n_i = sum_b w_ib rot(S_b) n0_i, linear in the skinning
// rotations and not renormalized, so that its derivative (kinematic_jacobians.h) is exact.
// It is not the true normal of the skinned surface (Tarini et al. 2014); callers that
// need unit normals normalize the result themselves.
#ifndef MOCAPSOLVE_KINEMATICS_SKINNING_H_
#define MOCAPSOLVE_KINEMATICS_SKINNING_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/forward_kinematics.h"
#include "kinematics/skinned_mesh.h"

namespace mocapsolve {

// S_b = world_from_joint_b * joint_from_bind_b for every joint; `transforms` is resized.
void ComputeSkinningTransforms(const SkinnedMesh& mesh, const FkData& fk,
                               std::vector<Eigen::Isometry3d>* transforms);

Eigen::Vector3d SkinPosition(const SkinnedMesh& mesh,
                             const std::vector<Eigen::Isometry3d>& transforms, int vertex);
Eigen::Vector3d SkinNormal(const SkinnedMesh& mesh,
                           const std::vector<Eigen::Isometry3d>& transforms, int vertex);

// All vertices: 3 x #V positions and (if the mesh has normals) 3 x #V normals; `normals`
// may be null.
void SkinMesh(const SkinnedMesh& mesh, const std::vector<Eigen::Isometry3d>& transforms,
              Eigen::Matrix3Xd* positions, Eigen::Matrix3Xd* normals);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_SKINNING_H_
