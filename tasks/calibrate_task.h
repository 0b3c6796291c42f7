// Calibrating a subject: from a solved motion and the markers of the same take, where
// each marker sits on the skeleton (problems/marker_solve/calibration.h), with the marker
// file's scale and axes decided first, and the result as a Subject (subject.h) that
// solve, repair and the pipeline take. `mocapsolve calibrate` and the Python module's
// calibrate() both call RunCalibrate. Knows nothing of flags.
#ifndef MOCAPSOLVE_TASKS_CALIBRATE_TASK_H_
#define MOCAPSOLVE_TASKS_CALIBRATE_TASK_H_

#include <string>
#include <vector>

#include "io/json_writer.h"
#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "problems/marker_solve/calibration.h"
#include "problems/marker_solve/marker_observations.h"
#include "settings/calibrate_settings.h"
#include "tasks/fit_skeleton_task.h"

namespace mocapsolve {

struct SubjectCalibrationOptions {
  std::string axes = "x,y,z";   // Marker file -> skeleton axes (ParseAxes), or "auto" (the
                                // best of the 24 axis-aligned rotations).
  double marker_scale = 0.0;    // Marker units -> skeleton units; 0: from the units.
  int frame_offset = 0;         // Marker frame = motion frame + frame_offset.
  int min_valid_frames = 2;     // Markers valid in fewer matched frames are left out.
  const MarkerSet* attachments = nullptr;  // Joints to keep (offsets re-estimated); null: auto.
  std::string skeleton_path;    // Recorded in the subject (the skeleton's file).
  double amc_fps = 120.0;       // Recorded in the subject.
  std::string markers_name;     // Names the marker file in errors.
};

struct SubjectCalibration {
  Subject subject;
  CalibrationResult result;
  MarkerFileToModel transform;   // The file -> skeleton mapping used.
  std::vector<double> axis_rms;  // With axes "auto": RMS per AllAxisRotations() candidate.
};

// `trajectories` as read from the file (they are copied and mapped).
Status CalibrateSubject(const Skeleton& skeleton, const Motion& motion,
                        const MarkerTrajectories& trajectories,
                        const SubjectCalibrationOptions& options, SubjectCalibration* out);

struct CalibrateTaskResult {
  SubjectCalibration calibration;  // With settings.refit, its subject is the refit's.
  // settings.refit: the fit (FitSubjectToTake); refit_kept is false when its checks failed
  // and the calibrated subject was kept.
  SkeletonFitResult refit;
  bool refit_kept = false;
  JsonObject report;  // `--report` after the caller's file names: attach, axes, ..., per_marker.
  std::string table;  // The console table: axes, one line per marker, skipped ones, the RMS (no final newline).
  std::string refit_line;  // settings.refit: the refit's RMS and kept round (no final newline); else "".
};

// Settings checked as the CLI checks them (their options, then --attach: auto or a .json).
Status CheckCalibrateSettings(const CalibrateSettings& settings);

// `mocapsolve calibrate`: the attachments read (settings.attach), CalibrateSubject with
// `options`' mapping and paths (their frame_offset, min_valid_frames and attachments come
// from `settings`), the report and the table. With settings.refit, the subject is then
// refitted on the same markers as `fit_skeleton --template_subject` refits it (the calibrated
// subject as the template, fit_skeleton's and the per-frame solve's defaults, but on every
// frame of the take, at most 400 spread over it): calibration
// places each marker on the given motion's poses, which are not this project's solve of the
// markers (CMU's AMC: 11.7 mm RMS against the markers on 02_01), so the subject's offsets and
// lengths absorb that motion's errors; the refit alternates our per-frame solve with a
// length/offset fit until they agree (3.2 mm there). Its checks failing keeps the calibrated
// subject (the report says so). Lengths in mm where the skeleton's unit is
// known ("rms_mm"), else skeleton units.
Status RunCalibrate(const Skeleton& skeleton, const Motion& motion, const MarkerTrajectories& trajectories,
                    const CalibrateSettings& settings, SubjectCalibrationOptions options,
                    CalibrateTaskResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_CALIBRATE_TASK_H_
