#include "settings/propagate_settings.h"

namespace mocapsolve {

const OptionGroup<PropagateSettings>& PropagateSettingOptions() {
  using S = PropagateSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::ik_root_weight, "ik_root_weight", "per skeleton unit",
           "IK edit: pull of the root translation toward the original, per skeleton unit (0 lets the root slide "
           "freely).", 0.0)
      .Add(&S::harmonic_ground, "harmonic_ground", "",
           "--method=harmonic: weight of every frame's edge to a ground node held at 0, as a fraction of the "
           "graph's mean degree, so the field decays away from the edit. On 16_15 (arm edits at frames 30-400, "
           "default --knn) 0.002 follows the Green's falloff with correlation 0.90-0.94. 0 = pure harmonic, with "
           "the clip's ends held at 0 instead (correlation 0.24-0.96: often nearly flat).", 0.0)
      .Add(&S::spline_width, "spline_width", "frames", "--method=spline: half-width of the cubic bump, frames.")
      .Add(&S::keep_contacts, "keep_contacts",
           "Re-solve frames where a foot was planted in the source so that it stays where it was (legs absorb "
           "the edit; the root keeps it).")
      .Add(&S::contact_height_cm, "contact_height_cm", "cm",
           "Contact: foot joint at most this high above its lowest point in the clip (cm).", 0.0)
      .Add(&S::contact_speed_cm, "contact_speed_cm", "cm/s", "Contact: foot joint slower than this (cm/s).", 0.0)
      .Add(&S::contact_prior_cm, "contact_prior_cm", "cm",
           "Contact re-solve: cm of foot error worth one radian of change from the propagated pose (smaller: feet "
           "held tighter).", 0.0)
      .Add(&S::contact_blend_s, "contact_blend_s", "s",
           "Contact re-solve: seconds over which each leg correction eases in and out around planted frames (0 = "
           "off: legs pop).", 0.0)
      .Add(&S::compare_falloffs, "compare_falloffs",
           "Also compute the other falloffs of the first edit and report their correlation and largest "
           "difference with the chosen one.");
  return *group;
}

}  // namespace mocapsolve
