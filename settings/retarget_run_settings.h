// RetargetRunSettings: how `retarget` reads its source and target (the source's clip, the
// skins, whether a glTF source's mesh is tracked, its sampling, repeats), what it writes
// (the new clip's name, animation-only files) and whether it times its stages. Declared
// once: retarget; joint_map reads the skins, pipeline --animation_only. What the retarget
// minimizes: settings/retarget_settings.h.
#ifndef MOCAPSOLVE_SETTINGS_RETARGET_RUN_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_RETARGET_RUN_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct RetargetRunSettings {
  std::string source_animation;  // The source file's clip (name or index; "" = the first).
  std::string source_skin;       // Skins by name or index ("" = skin 0).
  std::string target_skin;
  bool source_mesh = true;       // Track a skinned glTF source's own mesh.
  double frame_rate = 0.0;       // Resample the source to this rate (0 = its key rate).
  int loop = 1;                  // Repeat the source clip N times (timing long clips).
  std::string animation_name;    // The new clip's name in --out; "" = "retargeted from ...".
  bool animation_only = false;   // Write skeleton, skin and the clip only (no meshes).
  bool stage_times = false;      // Time FK, skinning, Jacobian and solve separately (dls).
};

const OptionGroup<RetargetRunSettings>& RetargetRunSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_RETARGET_RUN_SETTINGS_H_
