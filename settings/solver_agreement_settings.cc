#include "settings/solver_agreement_settings.h"

namespace mocapsolve {

const OptionGroup<SolverAgreementSettings>& SolverAgreementOptions() {
  using S = SolverAgreementSettings;
  static const OptionGroup<S>* const group =
      &(*new OptionGroup<S>())
           .Add(&S::compare_solvers, "compare_solvers",
                "Also solve the take per frame with the other solver (dls and ceres, each from the same "
                "first-frame start, warm-started from its own previous frame) and report the frames whose "
                "final cost differs by more than --agreement_tolerance (the report's solver_agreement; a "
                "line on the console). The written motion is --solver's.")
           .Add(&S::agreement_tolerance, "agreement_tolerance", "",
                "--compare_solvers: two final costs agree when they differ by at most this fraction of the "
                "larger.", 0);
  return *group;
}

}  // namespace mocapsolve
