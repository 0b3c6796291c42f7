#include "apps/retarget_flags.h"

#include "settings/retarget_settings.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "apps/config_flags.h"
#include "apps/option_flags.h"
#include "apps/solver_flags.h"

// apps/propagate_command.cc: here the source joints to plant (default: names with foot, toe, ankle).
DECLARE_string(foot_joints);

DEFINE_bool(animation_only, false, "Write each retargeted .glb/.gltf as an animation-only glTF: the character's "
            "skeleton nodes (same names and rest transforms), its skin and the new animation, without meshes, "
            "materials or images; Blender (scripts/apply_animation_gltf.py) and three.js play it on the "
            "character file they already have.");

namespace mocapsolve {

RetargetSettings RetargetSettingsFromFlags() {
  RetargetSettings s;
  // --solver and --limit_weight: retarget's own (RetargetSolverOptions), or in pipeline the
  // marker solver's of the same names (dls by default there too).
  ReadOptionFlags(RetargetSolverOptions(), &s);
  ReadOptionFlags(RetargetSettingOptions(), &s);
  s.foot_joints = FLAGS_foot_joints;
  return s;
}

Status RetargetOptionsFromFlags(CharacterRetargetOptions* options) {
  return RetargetOptionsFromSettings(RetargetSettingsFromFlags(), options);
}

}  // namespace mocapsolve
