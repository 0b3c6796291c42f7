// Mesh mapping between two characters whose meshes differ (thesis 4.3.2, eq. 11).
//
// Both meshes are first brought into a common rest frame, normalized for height and root:
//   u = (x - origin) / height,  origin = (mean x, min y, mean z) of the rest vertices,
//   height = max y - min y (Y up, as glTF; both characters facing the same way),
// so that the feet sit at u_y = 0, the body is centred on the vertical axis and the top
// of the head is at u_y = 1. Each source sample s then maps to the target vertex
//   k(s) = argmin_k |u_t(k) - u_s(s)|                                  (eq. 11)
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
};

// From the rest (bind-pose) vertex positions, 3 x #V, #V > 0. A flat mesh gets height 1.
CharacterFrame ComputeCharacterFrame(const Eigen::Matrix3Xd& rest_positions);

// For each column s of `source_samples` (3 x #S, source rest positions of the samples),
// the index of the nearest column of `target_rest` (3 x #V_t) in the common frame.
std::vector<int> MapToNearestVertices(const Eigen::Matrix3Xd& source_samples,
                                      const CharacterFrame& source_frame,
                                      const Eigen::Matrix3Xd& target_rest,
                                      const CharacterFrame& target_frame);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_MESH_MAPPING_H_
