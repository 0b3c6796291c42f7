// SolverAgreementSettings: solve the take with both per-frame solvers and report the
// frames whose final cost differs (problems/marker_solve/solver_agreement.h). Declared
// once: solve.
#ifndef MOCAPSOLVE_SETTINGS_SOLVER_AGREEMENT_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_SOLVER_AGREEMENT_SETTINGS_H_

#include "settings/option.h"

namespace mocapsolve {

struct SolverAgreementSettings {
  bool compare_solvers = false;
  double agreement_tolerance = 0.01;  // Relative difference of the final costs.
};

const OptionGroup<SolverAgreementSettings>& SolverAgreementOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_SOLVER_AGREEMENT_SETTINGS_H_
