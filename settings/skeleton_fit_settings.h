// SkeletonFitSettings: the options of fitting a subject to a take's markers (`mocapsolve
// fit_skeleton`, Python's fit_skeleton()): the rounds of pose solve and length/offset fit,
// the constraints on bone scales and marker offsets, the outlier rule, the checks and the
// template label map. Declared once; the CLI's flags and Python's keywords. The fit itself:
// tasks/fit_skeleton_task.h.
#ifndef MOCAPSOLVE_SETTINGS_SKELETON_FIT_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_SKELETON_FIT_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct SkeletonFitSettings {
  int fit_iterations = -1;       // -1: 15 with a template subject, else 6.
  int attach_rounds = -1;        // -1: 12 with a template subject, else 0.
  int attach_iterations = 6;
  int fit_frame_step = 4;        // Frames.
  int fit_max_frames = 0;        // At most N, every k-th of the take (FitFrameStride); 0 = all frames.
  double max_skin_cm = 12.0;     // 0 = off.
  double min_bone_scale = 0.8;
  double max_bone_scale = 1.25;
  double offset_prior = 0.0;
  // Per-marker solve weights learned on the take (problems/marker_solve/marker_weights.h):
  // the lowest weight a loose marker gets; 0 = off (every marker weight 1).
  double learn_weights = 0.0;
  double fit_outlier_mm = 200.0;  // 0 = off.
  // Fit again with the template's locked rotation axes freed (problems/marker_solve/locked_axes.h),
  // kept when it predicts better (tasks/fit_skeleton_task.cc); only with attach rounds.
  bool free_locked_axes = true;
  std::string check = "fail";    // fail | warn | off.
  // TEMPLATE:TAKE pairs or their file (problems/marker_solve/template_labels.h); "auto": a
  // shipped map that fits the take (template_label_maps.h); "" or "none": none.
  std::string template_labels = "auto";
  // Marker association from the data (problems/marker_solve/marker_association.h): auto
  // (when fewer than 3 template labels are in the take and no map is given), always, never.
  std::string associate = "auto";
  double min_association_confidence = 0.6;
};

const OptionGroup<SkeletonFitSettings>& SkeletonFitSettingOptions();

// The same options for the subject `pipeline --subject=auto` fits on the fly (batch's takes,
// Python's pipeline(subject='auto')): the fit on at most 600 frames by default, spread over
// the whole take (a fit's time grows with the frames; 600 fit the shared captures,
// BENCHMARKS.md).
const OptionGroup<SkeletonFitSettings>& AutoSubjectFitOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_SKELETON_FIT_SETTINGS_H_
