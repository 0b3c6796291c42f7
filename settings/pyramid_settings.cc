#include "settings/pyramid_settings.h"

#include <string>

namespace mocapsolve {

const OptionGroup<PyramidSettings>& PyramidSettingOptions() {
  using S = PyramidSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::kernel_a, "kernel_a", "",
           "Centre weight a of the 5-tap generating kernel (b = 1/4, c = 1/4 - a/2; eq. 1), in [0.25, 0.75].", 0.25,
           0.75)
      .Add(&S::tension, "tension", "", "Tension of the cubic Cardinal spline of EXPAND, in [0, 1] (0 = Catmull-Rom).",
           0.0, 1.0);
  return *group;
}

Status PyramidOptionsFromSettings(const PyramidSettings& settings, int levels, PyramidOptions* options) {
  Status status = PyramidSettingOptions().Validate(settings);
  if (!status.ok()) return status;
  *options = PyramidOptions();
  options->kernel.a = settings.kernel_a;
  options->tension = settings.tension;
  options->levels = levels;
  status = options->Validate();
  if (!status.ok()) return Status::Error("--levels: " + status.message());
  return Status::Ok();
}

}  // namespace mocapsolve
