#include "settings/skeleton_fit_settings.h"

namespace mocapsolve {

const OptionGroup<SkeletonFitSettings>& SkeletonFitSettingOptions() {
  using S = SkeletonFitSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::fit_iterations, "fit_iterations", "",
           "Alternations of pose solve and length/offset fit on the template's markers; -1: 15 with "
           "--template_subject, else 6.", -1, 100)
      .Add(&S::attach_rounds, "attach_rounds", "",
           "Rounds of attaching every marker of the take to the fitted skeleton (auto: the joint it moves least "
           "with, among joints whose bone is within --max_skin_cm) and fitting again (stopping early when a round "
           "improves the marker RMS by less than 1 %); -1: 12 with --template_subject, else 0.", -1, 20)
      .Add(&S::attach_iterations, "attach_iterations", "", "Fit iterations in each attach round.", 0, 100)
      .Add(&S::fit_frame_step, "fit_frame_step", "frames", "Use every N-th frame in the length/offset fit.", 1)
      .Add(&S::fit_max_frames, "fit_max_frames", "frames", "Fit on at most N frames, spread over the whole take: every k-th frame, k = ceil(frames / N) (a take "
           "that starts still still shows its later poses); 0 = all.", 0)
      .Add(&S::max_skin_cm, "max_skin_cm", "cm",
           "Markers stay within this distance of their bone (fit and attach); 0: off.", 0.0)
      .Add(&S::min_bone_scale, "min_bone_scale", "",
           "Bone lengths no shorter than this times the template's (in (0, 1]).", 0.0, 1.0)
      .Add(&S::max_bone_scale, "max_bone_scale", "", "Bone lengths no longer than this times the template's.",
           1.0)
      .Add(&S::offset_prior, "offset_prior", "",
           "Weight of the prior that keeps marker offsets near the template's in the first fit, per frame, "
           "relative to a marker residual; 0: off.", 0.0)
      .Add(&S::learn_weights, "learn_weights", "",
           "Learn each marker's solve weight on the take: 1/sigma^2 of its residual spread in a solve of the fitted "
           "subject, relative to the median marker's, at most 1 and at least this (soft tissue: upper arm, thigh); "
           "written in the subject's marker set; 0: off (every marker weight 1).", 0.0, 1.0)
      .Add(&S::fit_outlier_mm, "fit_outlier_mm", "mm",
           "Leave out of every round's fit the samples of the template's markers farther than this, and than 5 "
           "times their marker's median residual, from their marker in the first fit (mislabels, ghosts); the fit "
           "RMS and the checks are then over the kept samples, and the report counts the others; 0: fit every "
           "sample.", 0.0)
      .Add(&S::free_locked_axes, "free_locked_axes",
           "With attach rounds: fit the take again with the template's joints that lock one rotation axis which no "
           "joint below them makes up (an ASF foot's roll about its heel-toe axis), observed by at least 3 markers on "
           "or below them, given that axis, and keep that fit when its held-out leave-one-out median on the fitted "
           "frames is lower (the fit then takes about twice as long); false: the template's axes.")
      .Add(&S::check, "check",
           "The subject checks (marker within 15 cm of its bone, or within its template distance when larger, "
           "torso direction within 15 degrees of the markers', left/right within 5 %, marker RMS within 25 mm): "
           "fail (exit 1, nothing written but the report), warn, off.",
           {"fail", "warn", "off"})
      .Add(&S::template_labels, "template_labels",
           "Template markers that are the take's under other labels: TEMPLATE:TAKE pairs (RFWT:RASI,LFWT:LASI) or "
           "a file of them (examples/ais_to_cmu_labels.txt); round 0 fits them under the take's labels, which the "
           "fitted subject keeps. auto: the first shipped map (examples/*_to_cmu_labels.txt) whose take labels are "
           "all in the take and whose template labels are all in the template but none in the take; \"\" or none: "
           "labels as they are.")
      .Add(&S::associate, "associate",
           "Which body segment each marker rides on, from the data when labels do not say: markers that move "
           "rigidly together form a segment, the segments' layout (feet lowest, head highest, left/right about the "
           "pelvis) names it, the up axis and units come from a body 1-2 m tall; non-marker points (model outputs, "
           "static or rarely seen points) are left out. Round 0 then fits every associated marker on its segment's "
           "joint and the detected axes and scale replace --axes/--marker_scale. auto: when fewer than 3 of the "
           "template's labels are in the take and --template_labels names no map; always; never. A take fitted by "
           "its labels still loses the points that are surely no markers (model outputs at the file's origin or far "
           "from the body, points rigid with nothing) unless the template names them.",
           {"auto", "always", "never"})
      .Add(&S::min_association_confidence, "min_association_confidence", "",
           "Associated markers below this confidence are left out of round 0; the attach rounds attach every marker "
           "to the joint it moves least with (associated ones too).", 0.0, 1.0);
  return *group;
}

const OptionGroup<SkeletonFitSettings>& AutoSubjectFitOptions() {
  static const OptionGroup<SkeletonFitSettings>* const group = new OptionGroup<SkeletonFitSettings>(
      SkeletonFitSettingOptions().WithDefault(
          "fit_max_frames", "600",
          "--subject=auto: fit the subject on at most N frames, every k-th frame of the take, k = ceil(frames / N) "
          "(0 = all; the pipeline then solves every frame with it)."));
  return *group;
}

}  // namespace mocapsolve
