#include "apps/falloff_flags.h"

#include "apps/option_flags.h"

#include "settings/falloff_settings.h"

namespace mocapsolve {

Status FalloffOptionsFromFlags(int num_frames, FalloffOptions* options) {
  FalloffSettings s;
  ReadOptionFlags(FalloffSettingOptions(), &s);
  return FalloffOptionsFromSettings(s, num_frames, options);
}

}  // namespace mocapsolve
