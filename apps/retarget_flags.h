// The retargeting knobs `retarget` and `pipeline` share (gflags, defined here), turned
// into CharacterRetargetOptions in one place.
#ifndef MOCAPSOLVE_APPS_RETARGET_FLAGS_H_
#define MOCAPSOLVE_APPS_RETARGET_FLAGS_H_

#include <gflags/gflags.h>

#include "kinematics/status.h"
#include "settings/retarget_settings.h"
#include "problems/retarget/retarget_character.h"

DECLARE_string(joint_map);
DECLARE_int32(subsample);
// Not a retargeting knob but how the result is delivered (io/gltf_writer.h); retarget and
// pipeline read it.
DECLARE_bool(animation_only);

namespace mocapsolve {

// Comma-separated names of the retarget option flags (Command::shared_flags style).
inline constexpr const char* kRetargetOptionFlagNames = kRetargetSettingNames;

// From the flags above, --solver (dls | dls_generic | ceres; dls when not given) and
// --limit_weight; reads the --blend_mask and --joint_map files.
Status RetargetOptionsFromFlags(CharacterRetargetOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_RETARGET_FLAGS_H_
