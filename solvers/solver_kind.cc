#include "solvers/solver_kind.h"

namespace mocapsolve {

bool ParseSolverKind(const std::string& name, SolverKind* kind) {
  if (name == "dls") return *kind = SolverKind::kDls, true;
  if (name == "dls_generic") return *kind = SolverKind::kDlsGeneric, true;
  if (name == "ceres") return *kind = SolverKind::kCeres, true;
  return false;
}

const char* SolverKindName(SolverKind kind) {
  switch (kind) {
    case SolverKind::kDls: return "dls";
    case SolverKind::kDlsGeneric: return "dls_generic";
    case SolverKind::kCeres: return "ceres";
  }
  return "?";
}

}  // namespace mocapsolve
