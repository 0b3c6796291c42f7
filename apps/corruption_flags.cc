#include "apps/corruption_flags.h"

#include "apps/option_flags.h"
#include "settings/corruption_settings.h"

namespace mocapsolve {

CorruptionSettings CorruptionSettingsFromFlags() {
  CorruptionSettings settings;
  ReadOptionFlags(CorruptionSettingOptions(), &settings);
  return settings;
}

Status CorruptionOptionsFromFlags(const LengthUnit& unit, CorruptionOptions* options) {
  return CorruptionOptionsFromSettings(CorruptionSettingsFromFlags(), unit, options);
}

}  // namespace mocapsolve
