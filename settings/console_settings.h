// ConsoleSettings: what every command prints besides its outputs. Declared once; every
// command has it (apps/main.cc registers it for each).
#ifndef MOCAPSOLVE_SETTINGS_CONSOLE_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_CONSOLE_SETTINGS_H_

#include "settings/option.h"

namespace mocapsolve {

struct ConsoleSettings {
  bool quiet = false;         // No progress on stderr.
  bool print_config = false;  // Print the options in force as a config file, and exit.
};

const OptionGroup<ConsoleSettings>& ConsoleSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_CONSOLE_SETTINGS_H_
