#include "settings/console_settings.h"

namespace mocapsolve {

const OptionGroup<ConsoleSettings>& ConsoleSettingOptions() {
  using S = ConsoleSettings;
  static const OptionGroup<S>* const group =
      &(*new OptionGroup<S>())
           .Add(&S::quiet, "quiet", "No progress output on stderr.")
           .Add(&S::print_config, "print_config",
                "Print every option of the command with its value (the defaults, or --config's) as a JSON config "
                "file, and exit.");
  return *group;
}

}  // namespace mocapsolve
