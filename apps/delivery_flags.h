// The delivery options (settings/delivery_settings.h: --frames, --seconds, --out_fps) as
// this run's flags give them, for the commands that write a clip (pipeline, retarget,
// convert; batch checks them before passing them on).
#ifndef MOCAPSOLVE_APPS_DELIVERY_FLAGS_H_
#define MOCAPSOLVE_APPS_DELIVERY_FLAGS_H_

#include "apps/option_flags.h"
#include "settings/delivery_settings.h"

namespace mocapsolve {

inline Status ClipDeliveryFromFlags(ClipDelivery* delivery) {
  DeliverySettings settings;
  ReadOptionFlags(DeliverySettingOptions(), &settings);
  return ClipDeliveryFromSettings(settings, delivery);
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_DELIVERY_FLAGS_H_
