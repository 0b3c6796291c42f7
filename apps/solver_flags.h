// The solver knobs every solving command shares (gflags, defined in solver_flags.cc),
// turned into options in one place: the SetOptionsFromFlags seam of STYLE.md.
#ifndef MOCAPSOLVE_APPS_SOLVER_FLAGS_H_
#define MOCAPSOLVE_APPS_SOLVER_FLAGS_H_

#include <gflags/gflags.h>

#include "kinematics/status.h"
#include "pipeline/solver_settings.h"
#include "problems/marker_solve/marker_clip_solver.h"
#include "problems/marker_solve/marker_frame_solver.h"

DECLARE_string(solver);
DECLARE_string(mode);

namespace mocapsolve {

// Comma-separated names of the flags below, for Command::shared_flags style help.
inline constexpr const char* kSolverFlagNames = kSolverSettingNames;

// The flags as settings (pipeline/solver_settings.h), --v=1 as verbose.
SolverSettings SolverSettingsFromFlags();

// Per-frame options (--solver picks Ceres or DLS); the skeleton's unit converts the
// prior weight from mm.
Status MarkerSolveOptionsFromFlags(const LengthUnit& skeleton_unit, MarkerSolveOptions* options);
// Whole-clip options (always Ceres; --linear_solver defaults to sparse_normal_cholesky).
Status ClipSolveOptionsFromFlags(ClipSolveOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_SOLVER_FLAGS_H_
