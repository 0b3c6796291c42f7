#include "apps/command.h"

namespace mocapsolve {

// Defined in apps/<name>_command.cc.
extern const Command kInfoCommand;
extern const Command kConvertCommand;
extern const Command kFkCommand;
extern const Command kGenerateCommand;
extern const Command kBenchCommand;
extern const Command kSolveCommand;
extern const Command kMarkersCommand;
extern const Command kCalibrateCommand;

const std::vector<Command>& AllCommands() {
  static const std::vector<Command> commands = {kInfoCommand, kConvertCommand, kFkCommand,
                                                kGenerateCommand, kBenchCommand,
                                                kSolveCommand,
                                                kMarkersCommand, kCalibrateCommand};
  return commands;
}

}  // namespace mocapsolve
