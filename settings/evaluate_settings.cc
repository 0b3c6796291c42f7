#include "settings/evaluate_settings.h"

namespace mocapsolve {

const OptionGroup<EvaluateSettings>& EvaluateSettingOptions() {
  using S = EvaluateSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::trials, "trials", "trials", "Damage draws to average over (seeds --seed, +1, ...).", 1, 1000)
      .Add(&S::white_noise_mm, "white_noise_mm", "mm",
           "--method=small_errors: white noise (mm per axis) added to every sample before the damage, and to the "
           "undamaged take the own detections come from (a noise-free synthetic take: 1).", 0.0)
      .Add(&S::protocol, "protocol",
           "--method=leave_one_out: cross_take: the subject as given (calibrated or fitted on another take of the "
           "actor), every frame scored; time_split: a subject fitted (as fit_skeleton, from --subject as the "
           "template) on the first half of the take, the second half scored. Either way no sample of a left-out "
           "marker on the scored frames reaches its prediction.",
           {"cross_take", "time_split"})
      .Add(&S::refine_offsets, "refine_offsets", "rounds",
           "--method=leave_one_out: per left-out marker, re-estimate the other markers' offsets on the scored frames "
           "(towards the subject's, --refine_prior_frames) and solve again, this many times (0: the subject as is).",
           0, 20)
      .Add(&S::refine_prior_frames, "refine_prior_frames", "frames",
           "The subject's offset in --refine_offsets counts as this many frames of observation.", 0.0)
      .Add(&S::off_body_mm, "off_body_mm", "mm",
           "--method=leave_one_out: leave out of the solve that predicts a marker the other markers' samples that the "
           "body cannot have put where they are (further from another marker than the skeleton reaches, by more than "
           "this tolerance: a marker fallen off, a point on the floor), found without the left-out marker; its own "
           "samples are all scored, and the report counts those off the body. 0 = every sample solved.",
           0.0);
  return *group;
}

}  // namespace mocapsolve
