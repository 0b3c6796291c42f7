// Skeleton fitting: bone lengths and marker offsets of a subject from its markers alone,
// for captures that come without a skeleton (issue 4's natural-gap takes).
//
// Alternation (as subject calibration in commercial solvers):
//   1. poses: the per-frame solve of the markers on the current skeleton (SolveSequence);
//   2. lengths and offsets: every marker is linear in the bone-length scales s_a
//      (offset_a <- s_a * offset_a) and its offsets z_mk at the current rotations:
//        x_m(f) = t(f) + sum_k w_mk ( sum_{a in path(j_mk), a != root} R_parent(a)(f) s_a o_a
//                                    + R_{j_mk}(f) z_mk )
//      One Gauss-Newton step on (s, z) with every frame's pose (root translation and
//      rotation dofs) eliminated to first order (a Schur complement per frame), so the
//      step knows the poses will follow; plain alternation with the rotations held
//      converges linearly, slowly where lengths and offsets trade off. The step is
//      damped (Levenberg-Marquardt) and kept only if the pose solve on the new skeleton
//      fits the markers better; otherwise the damping grows. A ridge of
//      relative weight `scale_ridge` damps the scale step, so bones no marker measures
//      keep their length; scales are clamped to [min_scale, max_scale] per step.
// With `symmetric`, a left and a right bone share one scale (names that differ only in a
// leading l/r or Left/Right, any case: lfemur/rfemur, LeftUpLeg/RightUpLeg), which
// halves the unknowns and keeps a limb from growing to make up for its marker offsets.
// End sites are scaled with their joint's bone (the mean scale of the joint's children,
// else its own). Frames are subsampled (every `frame_step`-th) for step 2.
// Constraints (a low residual bought with absurd offsets is a failed fit): each bone's
// total scale relative to the template stays in [min_scale, max_scale] (default 0.8 ..
// 1.25), left and right share a scale, the rest pose (bone directions, rest rotations)
// is the template's, and with max_bone_distance every marker stays within that skin
// distance of its bone (or within its starting distance, when the given set already holds
// it farther out: clamping a trusted template marker would make the fit worse than its
// start and every step would be refused). subject_checks.h measures the result without trusting the
// residual.
// Outliers (with outlier_distance > 0): a sample farther than outlier_distance, and than 5
// times its marker's median residual, from its marker on the first pose solve is left out of
// the whole fit (poses and lengths/offsets), and the poses are solved again, up to 3 times
// while new ones appear. A mislabelled or ghost sample
// (nick_freeform_001's RTOE label on a marker 1 m up for its last 126 frames) is otherwise
// fitted like any other: least squares moves the leg toward it and skews every bone.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SKELETON_FIT_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SKELETON_FIT_H_

#include <functional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

struct SkeletonFitOptions {
  int iterations = 6;
  int frame_step = 4;
  double scale_ridge = 1e-3;  // Relative to the largest diagonal entry of the scales' block.
  bool symmetric = true;
  // Bone-length scales relative to the template (anthropometric range): every bone's
  // total scale stays in [min_scale, max_scale].
  double min_scale = 0.8, max_scale = 1.25;
  // The scales the given skeleton already carries relative to the template (one per
  // joint; empty: all 1), so rounds of fitting keep one bound.
  std::vector<double> initial_scales;
  // Skin distance: after each step every marker offset is moved onto the tube of this
  // radius around its joint's bone (subject_checks.h, ClampToBone), or of its starting
  // distance when that is larger; skeleton units, 0: off.
  double max_bone_distance = 0.0;
  // Per joint (empty: none): held rigid with its parent through the fit (a held limb no
  // marker may attach to, held_segments.h, HeldLimbJoints); its bone counts as its
  // parent's for max_bone_distance (subject_checks.h, BoneSegments).
  std::vector<bool> held_limbs;
  // The first frame's root pose from the markers' geometry (sequence_solver.h), not the
  // 24 axis orientations.
  bool root_from_markers = false;
  // A prior on the marker offsets toward the ones the fit starts from (the template's,
  // or a fresh attachment's): offset_prior_weight * (frames used) * |z - z_start|^2 in the
  // length/offset step, so a marker's offset and its bones' lengths do not trade freely
  // (a knee marker stays at the knee, the knee between thigh and shin). 0: off.
  double offset_prior_weight = 0.0;
  // Samples farther than this (and than 5x their marker's median residual) from their marker
  // on the first pose solve are left out of the fit (skeleton units); 0: every sample is fitted.
  double outlier_distance = 0.0;
};

// Called after each pose solve of an iteration: (iteration, marker RMS of that solve).
using SkeletonFitProgress = std::function<void(int iteration, double rms)>;

struct SkeletonFitReport {
  std::vector<double> rms;          // Marker RMS before and after each iteration (skeleton units).
  std::vector<double> bone_scales;  // Per joint: its offset's overall scale relative to the
                                    // template (initial_scales times this fit's; 1 for the root).
  std::vector<std::pair<int, int>> outliers;  // (frame, marker) samples left out (outlier_distance).
};

// observed[f][m] in skeleton units (marker_observations.h). Writes the fitted skeleton
// and marker set, and the motion solved on them (one more pose solve after the last fit);
// report->rms is over the samples the fit kept (report->outliers are left out).
// frame_progress (optional): SolveSequence's frames done within each pose solve, with the
// step the solve belongs to (0: the solves before the first step, the outlier passes
// included; k: the solve of step k).
Status FitSkeletonToMarkers(const Skeleton& skeleton, const MarkerSet& markers,
                            const std::vector<std::vector<Eigen::Vector3d>>& observed,
                            const MarkerSolveOptions& solve_options, const SkeletonFitOptions& options,
                            Skeleton* fitted_skeleton, MarkerSet* fitted_markers, Motion* motion,
                            SkeletonFitReport* report, const SkeletonFitProgress& progress = nullptr,
                            const std::function<void(int step, int frames_done)>& frame_progress = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SKELETON_FIT_H_
