#include "settings/band_settings.h"

namespace mocapsolve {

const OptionGroup<BandSettings>& BandSettingOptions() {
  using S = BandSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::levels, "levels", "levels",
           "Pyramid levels N; the N finest bands are dropped (each level halves the rate: 2^N frames is the "
           "shortest period kept).")
      .Add(&S::weights, "weights",
           "Band weights w_0 (finest band),..,w_{N-1},w_N (the top Gaussian), comma-separated; N + 1 values build "
           "an N-level pyramid.");
  return *group;
}

}  // namespace mocapsolve
