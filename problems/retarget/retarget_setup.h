// Retarget setup (thesis 4.3.1-4.3.5): which target vertex tracks which source vertex,
// by position or by normal, and what it tracks in each frame.
//
// Tracked vertices: the source mesh is subsampled (vertex_subsampling.h, in its bind
// pose) and each sample s is mapped to the nearest target vertex k(s) in the common rest
// frame (mesh_mapping.h). The correspondence comes from the meshes only: the skeletons
// may differ in joint count, names and hierarchy.
//
// Goals, per frame f (target mesh units, target world frame): with the source's skinned
// position p_s and LBS normal n_s (eqs. 5-6, not renormalized) at frame f,
//   position goal  g = o_t + (h_t / h_s) (p_s - o_s)
//   normal goal    m = n_s
// where o, h are the characters' rest frames (CharacterFrame of the bind-pose meshes:
// feet-level origin, height).
// So positions are brought into the target's scale by the height ratio about the rest
// frames' origins: the source's global path (its root's travel) is scaled by the same
// ratio, and the target root translation is an unknown of each frame's solve, held
// in place by the position-tracked vertices (warm start: the previous frame, see
// retarget_clip.h).
//
// Normalization (4.3.3): sigma = the standard deviation of all position goals over the
// clip, sqrt(sum |g - mean g|^2 / (3 N)), computed once; position residuals are divided
// by sigma so they are on the scale of the (unit) normals.
//
// Blend mask (4.3.4): B_s = 0 (track the position) when the target vertex's cumulative
// skin weight (4.3.5) on the subtrees of the "position joints" is >= 0.5, else 1 (track
// the normal). Position joints: given by name (a blend-mask file), or automatically
// every target joint whose name contains hand, foot, toe or head (case-insensitive),
// i.e. the end effectors that touch the world. If no joint matches, every sample tracks
// its position (noted in RetargetSetup::notes).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_SETUP_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_SETUP_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"
#include "problems/retarget/mesh_mapping.h"
#include "problems/retarget/vertex_subsampling.h"

namespace mocapsolve {

struct RetargetSetupOptions {
  SubsampleOptions subsample;
  // Explicit position joints (target joint names); empty: automatic from the patterns.
  std::vector<std::string> position_joints;
  std::vector<std::string> position_name_patterns = {"hand", "foot", "toe", "head"};
  double position_weight_threshold = 0.5;
};

struct TrackedVertex {
  int source_vertex = -1;
  int target_vertex = -1;
  bool track_position = false;  // B = 0; otherwise the normal is tracked (B = 1).
};

struct RetargetSetup {
  std::vector<TrackedVertex> tracked;
  CharacterFrame source_frame, target_frame;
  double scale = 1.0;               // h_t / h_s.
  std::vector<int> position_joints;  // Target joints whose subtrees are position-tracked.
  std::vector<std::string> notes;    // Decisions worth reporting (fallbacks).
};

// The mesh as modelled (its bind pose, bind space = world at bind time): the rest
// positions and unit rest normals, 3 x #V each. Subsampling, mapping and the rest frames
// all use this pose, so both characters should be bound in similar poses (T or A).
void BindPoseMesh(const SkinnedMesh& mesh, Eigen::Matrix3Xd* positions, Eigen::Matrix3Xd* normals);

// Errors: a mesh without normals or vertices, an unknown position joint name.
Status BuildRetargetSetup(const SkinnedMesh& source_mesh, const Skeleton& target_skeleton, const SkinnedMesh& target_mesh,
                          const RetargetSetupOptions& options, RetargetSetup* setup);

// Per-frame goals of the tracked vertices (3 x #tracked each) and sigma.
struct RetargetGoals {
  std::vector<Eigen::Matrix3Xd> positions;
  std::vector<Eigen::Matrix3Xd> normals;
  double sigma = 1.0;
};

void ComputeRetargetGoals(const RetargetSetup& setup, const Skeleton& source_skeleton,
                          const SkinnedMesh& source_mesh, const Motion& source_motion,
                          RetargetGoals* goals);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_SETUP_H_
