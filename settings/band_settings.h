// BandSettings: which frequency bands of a Laplacian pyramid are kept: filter drops the
// --levels finest, bands scales each by its --weights. Declared once: filter, bands.
#ifndef MOCAPSOLVE_SETTINGS_BAND_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_BAND_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct BandSettings {
  int levels = 2;       // Pyramid levels N; filter drops the N finest bands.
  std::string weights;  // w_0 (finest),..,w_N (the top Gaussian), comma-separated.
};

const OptionGroup<BandSettings>& BandSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_BAND_SETTINGS_H_
