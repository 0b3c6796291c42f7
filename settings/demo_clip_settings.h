// DemoClipSettings: the length and rate of `mocapsolve generate`'s procedural demo clip
// (kinematics/demo_character.h). Declared once; the CLI's flags.
#ifndef MOCAPSOLVE_SETTINGS_DEMO_CLIP_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_DEMO_CLIP_SETTINGS_H_

#include "settings/option.h"

namespace mocapsolve {

struct DemoClipSettings {
  int frames = 240;
  double fps = 60.0;  // Frames per second.
};

const OptionGroup<DemoClipSettings>& DemoClipSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_DEMO_CLIP_SETTINGS_H_
