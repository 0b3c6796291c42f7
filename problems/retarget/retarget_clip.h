// RetargetClip: a whole source clip onto the target character, frame by frame (thesis
// Algorithm 4), with the quality figures the issue asks for.
//
// Loop: goals for every frame (retarget_setup.h: ComputeRetargetGoals, which also gives
// sigma), then per frame RetargetFrameSolver::Solve warm-started from the previous
// frame's solution (or from options.warm_start's pose of that frame). Frame 0 starts from options.start_pose (default: the skeleton's
// RestPose; for glTF characters pass the bind pose) with the root moved so that the
// centroid of the tracked target vertices lands on the centroid of the frame's position
// goals; the root translation is then solved with everything else (it is not copied
// from the source, whose skeleton may be unrelated).
// Foot plants (options.plant_contacts): see RetargetClipOptions.
// The output motion has the source's frame rate; non-root translations are the target's
// rest offsets.
//
// Figures (per frame and over the clip):
//   position error  mean |v - g| over all tracked vertices / target height;
//   normal error    mean angle between the target's and the source's LBS normals (degrees);
//   foot skating    over the tracked vertices weighted (>= 0.5) on joints named foot or toe:
//                   while the source's vertex is in contact (its goal's height above the
//                   target's rest floor < contact_height * target height in two
//                   consecutive frames), the horizontal (x, z) speed of the source's goal
//                   and of the result's vertex, averaged over those frame pairs, in target
//                   heights per second: does the result slide where the source is planted.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_CLIP_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_CLIP_H_

#include <functional>
#include <vector>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"
#include "problems/retarget/retarget_frame_solver.h"
#include "problems/retarget/retarget_setup.h"

namespace mocapsolve {

struct RetargetClipOptions {
  RetargetSolveOptions solve;
  double contact_height = 0.02;  // Fraction of the target height above its rest floor.
  Pose start_pose;  // Warm start of frame 0 (its root translation is re-centred); empty:
                    // RestPose(target skeleton).
  // Foot plants: per solve.plant_joints entry p, plant_contacts[p][f] = the joint is
  // planted at frame f (e.g. from the source's DetectFootContacts, edit_propagation/
  // foot_contacts.h). The first frame of a contact run is solved without its plant and
  // the joint's solved position becomes the anchor; the following frames of the run hold
  // it there (FootPlantResidual, weight solve.plant_weight / sigma).
  std::vector<std::vector<char>> plant_contacts;
  // Frame 0 is solved this many times in a row (each warm-started from the last): its
  // start pose may be far from the source's (another facing, a T-pose against a walk),
  // and every later frame starts from it.
  int first_frame_solves = 1;
  // Per-frame warm starts on the target skeleton (one pose per source frame), e.g. the
  // source's own motion when it is the target's skeleton (retarget_character.h): frame f
  // starts from warm_start.frames[f] (not re-centred; start_pose is then unused), and the
  // pose's non-root translations are kept (the solve moves rotations and the root only).
  // Empty: frame f starts from frame f - 1's solution.
  Motion warm_start;
  // Limb directions (solve.limbs, solve.limb_direction_weight > 0): per frame the goal
  // directions of the limbs, 3 x #solve.limbs, unit, target world (RetargetFrameSolver::
  // SetLimbGoals). Required then, one per source frame; unused otherwise.
  std::vector<Eigen::Matrix3Xd> limb_goals;
  // false: no solve, the warm start is the answer (its figures are measured as they are;
  // final_cost and iterations 0). Requires a warm start.
  bool run_solver = true;
};

struct RetargetFrameFigures {
  double position_error = 0.0;  // Fraction of target height.
  double normal_error_deg = 0.0;
  double effector_error = 0.0;  // Position-tracked vertices only, fraction of target height.
  double final_cost = 0.0;
  int iterations = 0;
};

struct RetargetClipResult {
  Motion motion;  // On the target skeleton.
  std::vector<RetargetFrameFigures> frames;
  double sigma = 0.0;
  double mean_position_error = 0.0;  // Fraction of target height, over frames.
  double max_position_error = 0.0;
  double mean_normal_error_deg = 0.0;
  double mean_effector_error = 0.0;  // Position-tracked vertices (end effectors), fraction of height.
  double mean_final_cost = 0.0;  // 1/2 |r|^2 after each frame's solve, averaged.
  int foot_vertices = 0;
  int contact_pairs = 0;  // (vertex, frame pair)s in contact.
  double source_foot_skating = 0.0;  // Target heights per second.
  double result_foot_skating = 0.0;
  double solve_seconds = 0.0;  // The frame loop (solves and their error figures).
  RetargetStageTimes stages;   // Lean DLS with time_stages only.
};

// Called after each frame with (frames done, total).
using RetargetProgressCallback = std::function<void(int, int)>;

Status RetargetClip(const Skeleton& source_skeleton, const SkinnedMesh& source_mesh,
                    const Motion& source_motion, const Skeleton& target_skeleton,
                    const SkinnedMesh& target_mesh, const RetargetSetup& setup,
                    const RetargetClipOptions& options, RetargetClipResult* result,
                    const RetargetProgressCallback& progress = nullptr);

// `start` with its root translated so that the centroid of the tracked target vertices
// lands on the centroid of `goal_positions` (3 x #tracked): the warm start of frame 0.
Pose RecenteredStartPose(const Skeleton& target_skeleton, const SkinnedMesh& target_mesh,
                         const RetargetSetup& setup, const Eigen::Matrix3Xd& goal_positions,
                         Pose start);

// Tracked vertices whose target vertex has cumulative weight >= 0.5 on joints named
// foot or toe (case-insensitive), as indices into setup.tracked.
std::vector<int> FootTrackedVertices(const Skeleton& target_skeleton, const SkinnedMesh& target_mesh,
                                     const RetargetSetup& setup);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_CLIP_H_
