#include "apps/corruption_flags.h"

#include <glog/logging.h>

#include "apps/option_flags.h"
#include "settings/corruption_settings.h"

namespace mocapsolve {

CorruptionSettings CorruptionSettingsFromFlags() {
  CorruptionSettings settings;
  // main.cc checked every declared option's value as it parsed the command line.
  const Status status = ReadOptionFlags(CorruptionSettingOptions(), &settings);
  CHECK(status.ok()) << status.message();
  return settings;
}

Status CorruptionOptionsFromFlags(const LengthUnit& unit, CorruptionOptions* options) {
  return CorruptionOptionsFromSettings(CorruptionSettingsFromFlags(), unit, options);
}

}  // namespace mocapsolve
