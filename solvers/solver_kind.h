// Who minimizes a problem's residual blocks, for every problem that offers the choice (the
// per-frame marker solve, the retarget's frame solve): the lean DLS kernel for kinematic
// trees (tree_dls_solver.h), the generic DLS solver on the same ceres::CostFunctions
// (dls_solver.h), or Ceres itself. Users name them dls, dls_generic and ceres.
#ifndef MOCAPSOLVE_SOLVERS_SOLVER_KIND_H_
#define MOCAPSOLVE_SOLVERS_SOLVER_KIND_H_

#include <string>

namespace mocapsolve {

enum class SolverKind { kDls, kDlsGeneric, kCeres };

// "dls", "dls_generic", "ceres"; false on an unknown name.
bool ParseSolverKind(const std::string& name, SolverKind* kind);
const char* SolverKindName(SolverKind kind);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SOLVERS_SOLVER_KIND_H_
