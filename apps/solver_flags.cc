#include "apps/solver_flags.h"

#include <glog/logging.h>

#include "apps/option_flags.h"

namespace mocapsolve {

SolverSettings SolverSettingsFromFlags() {
  SolverSettings settings;
  ReadOptionFlags(SolverOptions(), &settings);
  settings.verbose = FLAGS_v >= 1;
  return settings;
}

Status MarkerSolveOptionsFromFlags(const LengthUnit& skeleton_unit, MarkerSolveOptions* options) {
  return MarkerSolveOptionsFromSettings(SolverSettingsFromFlags(), skeleton_unit, options);
}

Status ClipSolveOptionsFromFlags(ClipSolveOptions* options) {
  return ClipSolveOptionsFromSettings(SolverSettingsFromFlags(), options);
}

}  // namespace mocapsolve
