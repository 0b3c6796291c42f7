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
extern const Command kFilterCommand;
extern const Command kBandsCommand;
extern const Command kBlendCommand;
extern const Command kRepairCommand;
extern const Command kLabelCommand;
extern const Command kCorruptCommand;
extern const Command kEvaluateCommand;
extern const Command kFitSkeletonCommand;
extern const Command kDistanceCommand;
extern const Command kPropagateCommand;
extern const Command kRetargetCommand;
extern const Command kJointMapCommand;
extern const Command kPipelineCommand;
extern const Command kBatchCommand;
extern const Command kViewCommand;
extern const Command kLiveCommand;

const std::vector<Command>& AllCommands() {
  static const std::vector<Command> commands = {kPipelineCommand, kBatchCommand, kLiveCommand, kInfoCommand, kConvertCommand, kFkCommand,
                                                kGenerateCommand, kBenchCommand,
                                                kSolveCommand, kLabelCommand, kRepairCommand, kCorruptCommand,
                                                kEvaluateCommand,
                                                kMarkersCommand, kCalibrateCommand, kFitSkeletonCommand,
                                                kFilterCommand, kBandsCommand, kBlendCommand,
                                                kRetargetCommand, kJointMapCommand, kDistanceCommand, kPropagateCommand,
                                                kViewCommand};
  return commands;
}

}  // namespace mocapsolve
