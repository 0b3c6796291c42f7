// FrameLimitSettings: work on the input's first frames only (a quick look at a long take,
// timing). Declared once: solve and retarget.
#ifndef MOCAPSOLVE_SETTINGS_FRAME_LIMIT_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_FRAME_LIMIT_SETTINGS_H_

#include "settings/option.h"

namespace mocapsolve {

struct FrameLimitSettings {
  int max_frames = 0;  // The first N frames; 0 = all.
};

const OptionGroup<FrameLimitSettings>& FrameLimitOption();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_FRAME_LIMIT_SETTINGS_H_
