// Mesh mapping between two characters whose meshes differ (thesis 4.3.2, eq. 11).
//
// Both meshes (in their bind pose, rotated into a Y-up world) are first brought into a
// common rest frame, normalized for height, root and facing:
//   u = F (x - origin) / height,  origin = (mean x, min y, mean z) of the rest vertices,
//   height = max y - min y,
// F a rotation about the vertical (Y) axis that turns the character to face +Z: the
// left-right axis is the horizontal direction of largest vertex spread (the arm span of
// a T or A pose), and of its two normals the forward one is the side the feet stick out
// to (the centroid of the vertices in the lowest 5% of the height, the feet, lies in
// front of the body's centroid: toes are longer than heels). So the feet sit at u_y = 0,
// the body is centred on the vertical axis facing +Z, and the top of the head is at
// u_y = 1. (A heuristic for standing bipeds; align_facing = false keeps F = I.) Each
// source sample s then maps to the target vertex
//   k(s) = argmin_k |u_t(k) - u_s(s)|                                  (eq. 11)
// (optionally with the normals in the distance, see MapToNearestVertices)
// (nearest neighbour, nanoflann kd-tree over the target's vertices). For a mesh mapped
// onto itself this returns the sample itself (or a coincident duplicate).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_MESH_MAPPING_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_MESH_MAPPING_H_

#include <vector>

#include <Eigen/Core>

namespace mocapsolve {

// Where a character stands in its rest pose: the common frame's origin and scale.
struct CharacterFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // Mesh units.
  double height = 1.0;                               // Mesh units, > 0.
  Eigen::Matrix3d facing = Eigen::Matrix3d::Identity();  // F: canonical from world.
};

// From the rest (bind-pose) vertex positions in the world, 3 x #V, #V > 0. A flat mesh
// gets height 1. The facing: the major horizontal axis of the vertices is left-right;
// forward is signed by `left` (the character's left in the world, e.g. role_sides.h:
// forward = left x up) when it has a horizontal part, else by where the lowest vertices
// lie (toes ahead of the ankles).
CharacterFrame ComputeCharacterFrame(const Eigen::Matrix3Xd& rest_positions, bool align_facing = true,
                                     const Eigen::Vector3d& left = Eigen::Vector3d::Zero());

// For each column s of `source_samples` (3 x #S, source rest positions of the samples),
// the index of the nearest column of `target_rest` (3 x #V_t) in the common frame. With
// normals (3 x #S and 3 x #V_t, unit, world; may be empty) and normal_weight > 0 the
// distance is that of the 6-vectors (u, normal_weight * F n): a nearby vertex whose
// surface faces the same way wins over a slightly nearer one on the other side of a thin
// part (fingers, armour plates). normal_weight is in heights per unit normal difference.
std::vector<int> MapToNearestVertices(const Eigen::Matrix3Xd& source_samples,
                                      const CharacterFrame& source_frame,
                                      const Eigen::Matrix3Xd& target_rest,
                                      const CharacterFrame& target_frame,
                                      const Eigen::Matrix3Xd& source_normals = Eigen::Matrix3Xd(),
                                      const Eigen::Matrix3Xd& target_normals = Eigen::Matrix3Xd(),
                                      double normal_weight = 0.0);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_MESH_MAPPING_H_
