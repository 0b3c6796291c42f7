// The solver knobs every solving command shares (declared once in settings/solver_settings.h,
// made flags by main.cc), turned into options in one place.
#ifndef MOCAPSOLVE_APPS_SOLVER_FLAGS_H_
#define MOCAPSOLVE_APPS_SOLVER_FLAGS_H_

#include <gflags/gflags.h>

#include "kinematics/status.h"
#include "settings/solver_settings.h"
#include "problems/marker_solve/marker_clip_solver.h"
#include "problems/marker_solve/marker_frame_solver.h"

namespace mocapsolve {

// The declared solver options (SolverOptions) as this run's flags made them (a command
// declares them in Command::options), --v=1 as verbose.
SolverSettings SolverSettingsFromFlags();

// Per-frame options (--solver picks Ceres or DLS); the skeleton's unit converts the
// prior weight from mm.
Status MarkerSolveOptionsFromFlags(const LengthUnit& skeleton_unit, MarkerSolveOptions* options);
// Whole-clip options (always Ceres; --linear_solver defaults to sparse_normal_cholesky).
Status ClipSolveOptionsFromFlags(ClipSolveOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_SOLVER_FLAGS_H_
