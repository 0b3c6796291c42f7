// The pybind11 module `mocapsolve` (python/): shared conversions of the binding files.
//
// One binding file per area (io, kinematics, solve, repair, retarget, propagate, pyramid,
// pipeline); each defines Bind<Area>(py::module_&), called from module.cc in that order.
// Bindings call the library; they hold no logic of their own beyond moving data:
//   - a Status error becomes ValueError with the same one-line message as the CLI, or
//     OSError when an input file does not exist (naming the file);
//   - options come as keyword arguments named like the CLI's flags, applied onto the
//     library's settings structs (settings/solver_settings.h, settings/repair_settings.h)
//     whose conversion validates them as the CLI does;
//   - arrays are float64 numpy arrays; marker positions are a view on the C++ storage
//     (frames, markers, 3), motions are copied (a Motion is not one contiguous block).
// Solves release the GIL (py::gil_scoped_release) so Python threads run takes in parallel.
#ifndef MOCAPSOLVE_PYTHON_BINDINGS_H_
#define MOCAPSOLVE_PYTHON_BINDINGS_H_

#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "io/json_writer.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"

namespace mocapsolve::python {

namespace py = pybind11;

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Throws ValueError(status.message()) when the status is an error.
void ThrowIfError(const Status& status);
// (n, 4) x, y, z, w: the numpy form of n rotations (a pose's, a subject's mean pose).
Array QuaternionArray(const QuaternionVector& rotations);
// Throws OSError(ENOENT) naming the path when it does not exist or is not readable.
void RequireReadable(const std::string& path);

// Sets each keyword argument by name on the first of `settings` (bound settings objects)
// that has it; an unknown name raises TypeError naming it and the accepted names.
void ApplyKeywords(const py::kwargs& keywords, const std::vector<py::object>& settings,
                   const std::string& accepted);
// A task's report (what the CLI's --report writes) as Python dicts and lists.
py::object ReportToPython(const JsonObject& report);
// Whether a keyword of that name was given.
bool HasKeyword(const py::kwargs& keywords, const char* name);

// Shared, immutable models held by Python objects.
using SkeletonPtr = std::shared_ptr<Skeleton>;
using MarkersPtr = std::shared_ptr<MarkerTrajectories>;
using SubjectPtr = std::shared_ptr<Subject>;

// Missing samples are NaN in positions(): a sample whose position Python set to NaN (or
// set from NaN to a number) gets its mask updated to match before C++ reads it.
void SyncMask(MarkerTrajectories* markers);

// (frames, joints, 4) x,y,z,w / (frames, joints, 3) / (frames, 3) copies of a motion.
Array MotionRotations(const Motion& motion);
Array MotionTranslations(const Motion& motion);
Array RootTranslations(const Motion& motion);
// ValueError (ValidateMotion's / ValidatePose's message) unless motion / pose fits skeleton:
// every function where a skeleton meets a motion or pose checks this first.
void CheckMotion(const Skeleton& skeleton, const Motion& motion);
void CheckPose(const Skeleton& skeleton, const Pose& pose, const char* what);
// ValueError naming `what` unless every value is finite.
void CheckFinite(const Array& array, const char* what);

// The object behind a pointer or holder parameter. pybind11's conversion pass loads None
// into a parameter of a bound class's pointer or holder type (shared_ptr) as null, so each
// such parameter goes through this: TypeError "name: expected a T, got None".
std::string BoundTypeName(const std::type_info& type);
template <class T>
T& Required(T* object, const char* name) {
  if (object == nullptr) throw py::type_error(std::string(name) + ": expected a " + BoundTypeName(typeid(T)) + ", got None");
  return *object;
}
template <class T>
T& Required(const std::shared_ptr<T>& object, const char* name) { return Required(object.get(), name); }

// Checks an array's shape against (frames?, dims...) with -1 for any; error names `what`.
void CheckShape(const Array& array, const std::vector<py::ssize_t>& shape, const char* what);

// observed[f][m] <-> (frames, markers, 3) with NaN for missing samples.
Array ObservationsToArray(const std::vector<std::vector<Eigen::Vector3d>>& observed);
std::vector<std::vector<Eigen::Vector3d>> ArrayToObservations(const Array& array);


void BindIo(py::module_& m);
void BindKinematics(py::module_& m);
void BindSolve(py::module_& m);
void BindRepair(py::module_& m);
void BindRetarget(py::module_& m);
void BindPropagate(py::module_& m);
void BindPyramid(py::module_& m);
void BindPipeline(py::module_& m);
void BindSkeletonFitting(py::module_& m);

}  // namespace mocapsolve::python

#endif  // MOCAPSOLVE_PYTHON_BINDINGS_H_
