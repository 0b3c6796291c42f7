// Shared by the binding files that solve takes (solve, repair, pipeline): takes given as
// a path, Markers or a Take, and solver settings from keyword arguments.
#ifndef MOCAPSOLVE_PYTHON_SOLVE_BINDINGS_H_
#define MOCAPSOLVE_PYTHON_SOLVE_BINDINGS_H_

#include <memory>

#include "settings/solver_settings.h"
#include "pipeline/subject.h"
#include "python/bindings.h"

namespace mocapsolve::python {

using MarkerTakePtr = std::shared_ptr<MarkerTake>;

// `markers` a Take (returned as is) or a .c3d/.trc path loaded for the subject.
MarkerTakePtr TakeArgument(const Subject& subject, py::object markers);
// TakeArgument for the functions that solve it (solve, repair, evaluate): a take with no
// data, or with a segment never observed, raises as the CLI refuses it (RequireTakeData).
MarkerTakePtr SolvableTakeArgument(const Subject& subject, py::object markers);

// SolverSettings (SolverOptions' defaults) with the keywords applied; unknown keywords
// raise TypeError.
SolverSettings SettingsFromKeywords(const py::kwargs& keywords);

}  // namespace mocapsolve::python

#endif  // MOCAPSOLVE_PYTHON_SOLVE_BINDINGS_H_
