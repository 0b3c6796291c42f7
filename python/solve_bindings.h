// Shared by the binding files that solve takes (solve, repair, pipeline): takes given as
// a path or a Take, solver settings from keyword arguments, solve reports as dicts.
#ifndef MOCAPSOLVE_PYTHON_SOLVE_BINDINGS_H_
#define MOCAPSOLVE_PYTHON_SOLVE_BINDINGS_H_

#include <memory>

#include "settings/solver_settings.h"
#include "pipeline/subject.h"
#include "problems/marker_solve/sequence_solver.h"
#include "python/bindings.h"

namespace mocapsolve::python {

using MarkerTakePtr = std::shared_ptr<MarkerTake>;

// `markers` a Take (returned as is) or a .c3d/.trc path loaded for the subject.
MarkerTakePtr TakeArgument(const Subject& subject, py::object markers);

// SolverSettings with the keywords applied (default_solver, if not null, replaces
// "ceres" as the default of `solver`); unknown keywords raise TypeError.
SolverSettings SettingsFromKeywords(const py::kwargs& keywords, const char* default_solver);

py::dict SequenceReportDict(const SequenceSolveReport& report, const LengthUnit& unit);

}  // namespace mocapsolve::python

#endif  // MOCAPSOLVE_PYTHON_SOLVE_BINDINGS_H_
