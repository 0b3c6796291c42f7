// Marker calibration: where each marker sits on the skeleton, from a solved motion and
// the marker trajectories of the same take (the input of marker solving, eq. 9).
//
// Model. Marker m rides rigidly on joint j with offset z (joint j's frame, skeleton
// units): x_m(f) = p_j(f) + R_j(f) z, with (R_j(f), p_j(f)) = world_from_joint_j at
// motion frame f (forward_kinematics.h). Observed samples y_m(f) (model world axes,
// skeleton units, see "Marker files" below) are matched to motion frame f through
//   marker frame index = motion frame index + frame_offset;
// frames outside either clip and missing samples are skipped.
//
// Offsets. For a fixed joint, sum_f |p_j + R_j z - y_m|^2 = sum_f |z - l_mj(f)|^2 with
// the local position l_mj(f) = R_j(f)^T (y_m(f) - p_j(f)), so the least-squares offset is
// the mean local position and the residual RMS is the spread of l_mj about its mean:
//   z_mj = mean_f l_mj(f),   rms_mj = sqrt(mean_f |l_mj(f) - z_mj|^2).
// Auto attach: each marker rides on the joint in whose frame it moves least,
//   j*(m) = argmin_j rms_mj,
// over all joints (or options.candidate_joints). Joints whose frames move together
// (a joint without rotation channels, e.g. the ASF hip joints, moves rigidly with its
// parent) give the same rms up to round-off; among joints within
// tie_tolerance of the best (relative, plus an absolute 1e-9 of the marker's mean distance
// from the root, squared) the lowest index (the ancestor) wins, so results are
// deterministic, unless a tied joint's bone is clearly nearer (tie_nearer_factor).
// CalibratedMarker::runner_up names the best joint outside that tie.
// Fixed attachments (a marker set given): the joints (and weights) come from it and only
// the offsets are re-estimated; a blended marker x = sum_k w_k (p_k + R_k z_k) is linear
// in (z_1..z_K), solved by least squares over all frames (minimum norm when the joints
// move together and the split between them is not determined).
//
// Marker files in the model's frame. Marker files have their own axes and unit (C3D: mm,
// often Z-up); the model (BVH, ASF/AMC) its own. A sample is mapped by MarkerFileToModel
// (marker_observations.h): y_model = scale * A * y_file + translation, A a signed axis
// permutation with det +1 ("--axes=y,z,x" means (x, y, z)_model = (y, z, x)_file).
// Measured on CMU 02_01 (tests/problems/calibration_test.cc): CMU C3D (mm, Z-up) ->
// ASF/AMC (1/0.45 inch, Y-up) is A = "y,z,x", scale = 1 / 56.444 (the units' ratio), no
// translation: of the 24 axis rotations only y,z,x calibrates below 100 mm RMS (11.7
// mm); letting a translation float improves it by 0.4 mm only (t = (4, 8, 6) mm, noise),
// and a scale factor off by 0.5% in either direction makes it worse.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_CALIBRATION_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_CALIBRATION_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "kinematics/units.h"
#include "problems/marker_solve/marker_observations.h"

namespace mocapsolve {

// --- Axes of marker files -----------------------------------------------------------

// AxesName and AllAxisRotations: marker_observations.h.

// y <- transform.Apply(y) for every valid sample (residuals scaled by transform.scale);
// `unit` is set to new_unit. transform.scale > 0.
void TransformMarkers(const MarkerFileToModel& transform, const LengthUnit& new_unit,
                      MarkerTrajectories* trajectories);

// --- Calibration --------------------------------------------------------------------

struct CalibrationOptions {
  int frame_offset = 0;        // Marker frame index = motion frame index + frame_offset.
  int min_valid_frames = 2;    // Markers valid in fewer matched frames are skipped.
  std::vector<int> candidate_joints;  // Auto attach: joints allowed (empty: all).
  double tie_tolerance = 1e-6;        // Relative, on rms^2 (see the header comment).
  // Auto attach: only joints whose bone (subject_checks.h, BoneSegments) the marker's mean
  // local position lies within this distance of (skeleton units; 0: any joint). When no
  // joint qualifies, the joint with the nearest bone. Joints tied on the spread (moving
  // together in this motion) are told apart by the nearest bone, not the lowest index.
  double max_bone_distance = 0.0;
  // Auto attach without max_bone_distance: among joints tied on the spread the ancestor
  // (lowest index) wins, unless a tied joint's bone is this many times nearer to the
  // marker's mean local position (0: the ancestor always). A motion that never moves a
  // joint relative to its parent cannot tell them apart: CMU's 02_01 keeps the clavicles
  // at zero, so LSHO/RSHO tie between the thorax (3.2 units from its bone) and the
  // clavicle (0.8) and belong to the clavicle, on which later takes raise the shoulders
  // (leave-one-out on cmu_02_05, BENCHMARKS.md); sternum and C7 markers stay on the thorax.
  double tie_nearer_factor = 2.0;
};

struct CalibratedMarker {
  std::string label;       // Without subject prefix (SplitSubjectPrefix).
  int trajectory_index = -1;  // Index in the trajectories.
  int frames = 0;          // Matched frames where the marker was valid.
  double rms = 0.0;        // sqrt(mean_f |x_pred - y|^2), skeleton units.
  double max_error = 0.0;  // max_f |x_pred - y|, skeleton units.
  int runner_up = -1;      // Auto attach: best joint not tied with the chosen one (-1: none).
  double runner_up_rms = 0.0;
};

struct CalibrationResult {
  MarkerSet marker_set;  // Calibrated markers: trajectory order (auto) or the given set's.
  std::vector<CalibratedMarker> markers;  // Parallel to marker_set.
  std::vector<std::string> skipped;      // "LABEL: reason", one per marker left out.
  int first_motion_frame = 0;            // The matched range of motion frames,
  int matched_frames = 0;                // [first, first + matched).
  int samples = 0;                       // Valid samples used over all markers.
  double rms = 0.0;                      // Over all samples used, skeleton units.
};

// Calibrates every marker of `trajectories` (already in the model's axes and skeleton
// units, see TransformMarkers) against `motion`. attachments == nullptr: auto attach.
// Otherwise the markers of *attachments (matched by label, subject prefixes ignored)
// keep their joints and weights and get new offsets; markers the trajectories lack, or
// that are valid in too few frames, are skipped (listed in result->skipped), as are
// trajectory markers *attachments lacks. Errors: no overlapping frames, motion and
// skeleton of different sizes, a bad candidate joint, nothing left to calibrate.
Status CalibrateMarkers(const Skeleton& skeleton, const Motion& motion,
                        const MarkerTrajectories& trajectories, const CalibrationOptions& options,
                        const MarkerSet* attachments, CalibrationResult* result);

// Per-marker and overall RMS of a marker set against trajectories (same conventions as
// CalibrateMarkers; markers the trajectories lack are skipped): the figure a later
// solve on the same motion cannot beat.
Status EvaluateMarkerSet(const Skeleton& skeleton, const Motion& motion,
                         const MarkerTrajectories& trajectories, const MarkerSet& marker_set,
                         const CalibrationOptions& options, CalibrationResult* result);

// Auto axes: runs CalibrateMarkers for each of AllAxisRotations() on file-axes
// trajectories (already scaled to skeleton units, no translation) and returns the
// rotation of least RMS; *rms_per_candidate (optional) gets each candidate's RMS (AllAxisRotations()
// order, +inf where calibration failed).
Status FindMarkerAxes(const Skeleton& skeleton, const Motion& motion,
                      const MarkerTrajectories& file_axes_trajectories,
                      const CalibrationOptions& options, const MarkerSet* attachments,
                      Eigen::Matrix3d* model_from_file,
                      std::vector<double>* rms_per_candidate = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_CALIBRATION_H_
