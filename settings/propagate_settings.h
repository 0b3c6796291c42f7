// PropagateSettings: the edit-propagation knobs of `mocapsolve propagate` besides the
// falloff's (settings/falloff_settings.h) and the IK solve's (settings/solver_settings.h):
// the IK edit's root pull, the harmonic and spline falloffs' parameters, and the foot
// contacts held by --keep_contacts. Declared once; the CLI's flags and Python's keywords.
#ifndef MOCAPSOLVE_SETTINGS_PROPAGATE_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_PROPAGATE_SETTINGS_H_

#include "settings/option.h"

namespace mocapsolve {

struct PropagateSettings {
  double ik_root_weight = 1.0;      // Per skeleton unit of root translation.
  double harmonic_ground = 0.002;   // Fraction of the pose graph's mean degree.
  double spline_width = 30.0;       // Frames.
  bool keep_contacts = false;
  double contact_height_cm = 5.0;
  double contact_speed_cm = 20.0;   // cm/s.
  double contact_prior_cm = 1.0;    // cm of foot error per radian of change.
  double contact_blend_s = 0.2;     // Seconds.
  bool compare_falloffs = false;
};

const OptionGroup<PropagateSettings>& PropagateSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_PROPAGATE_SETTINGS_H_
