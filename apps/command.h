// The `mocapsolve <command>` front end: each sub-command lives in its own file
// (apps/<name>_command.cc) with its gflags DEFINE_*s at the top, and registers itself
// here. main.cc parses flags, prints help and turns a failed Status into one line on
// stderr and exit code 1.
#ifndef MOCAPSOLVE_APPS_COMMAND_H_
#define MOCAPSOLVE_APPS_COMMAND_H_

#include <string>
#include <vector>

#include "kinematics/status.h"
#include "settings/option.h"

namespace mocapsolve {

struct Command {
  const char* name;
  const char* summary;  // One line for `mocapsolve --help`.
  const char* usage;    // Usage and a paragraph of explanation for `mocapsolve NAME --help`.
  const char* source;   // __FILE__ of the command: main registers its options as flags of this file.
  // Positional arguments after flag parsing. Returns a failed Status on bad input.
  Status (*run)(const std::vector<std::string>& arguments);
  // The declared options the command reads (settings/option.h; the shared ones through
  // SharedOptions, apps/common_flags.h), groups in priority order:
  // main.cc registers them as this run's flags, the command's own (--help lists them); a
  // name two groups declare is the first group's. A command that needs another default or
  // meaning for an option declares its own (OptionGroup::WithDefault, settings/method_settings.h).
  std::vector<std::vector<Option>> options = {};
};

// Every command, in the order `--help` lists them.
const std::vector<Command>& AllCommands();

// A command that succeeds but must say more than "done" (pipeline: 3 = the take failed
// its quality gate, outputs written) sets the exit code main returns after committing
// the outputs.
void SetExitCodeOnSuccess(int code);

// The program's version (CMake's project version), for --version and reports.
const char* Version();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_COMMAND_H_
