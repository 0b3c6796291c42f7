#include <cerrno>
#include <cmath>
#include <fstream>

#include "python/bindings.h"

namespace mocapsolve::python {

Array QuaternionArray(const QuaternionVector& rotations) {
  Array out({static_cast<py::ssize_t>(rotations.size()), py::ssize_t{4}});
  for (size_t j = 0; j < rotations.size(); ++j) {
    const Eigen::Quaterniond& q = rotations[j];
    out.mutable_at(j, 0) = q.x(); out.mutable_at(j, 1) = q.y();
    out.mutable_at(j, 2) = q.z(); out.mutable_at(j, 3) = q.w();
  }
  return out;
}

void ThrowIfError(const Status& status) {
  if (!status.ok()) throw py::value_error(status.message());
}

void RequireReadable(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    PyErr_SetObject(PyExc_FileNotFoundError,
                    py::make_tuple(ENOENT, path + ": cannot open the file", path).ptr());
    throw py::error_already_set();
  }
}

void ApplyKeywords(const py::kwargs& keywords, const std::vector<py::object>& settings,
                   const std::string& accepted) {
  for (const auto& item : keywords) {
    const std::string name = py::str(item.first);
    py::object target;
    for (const py::object& candidate : settings) {
      if (name.rfind("_", 0) != 0 && py::hasattr(candidate, name.c_str())) {
        target = candidate;
        break;
      }
    }
    if (!target) {
      throw py::type_error("unexpected keyword argument '" + name + "' (options: " + accepted + ")");
    }
    try {
      target.attr(name.c_str()) = item.second;
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_TypeError)) throw;
      throw py::type_error(name + ": expected " +
                           std::string(py::str(target.attr(name.c_str()).get_type().attr("__name__"))) +
                           ", got " + std::string(py::repr(item.second)));
    }
  }
}

py::object ReportToPython(const JsonObject& report) {
  return py::module_::import("json").attr("loads")(report.ToString(/*indent=*/false));
}

bool HasKeyword(const py::kwargs& keywords, const char* name) { return keywords.contains(name); }

void SyncMask(MarkerTrajectories* markers) {
  for (int f = 0; f < markers->num_frames(); ++f) {
    for (int m = 0; m < markers->num_markers(); ++m) {
      const Eigen::Vector3d p = markers->position(f, m);
      const bool finite = p.allFinite();
      if (finite != markers->valid(f, m)) {
        if (finite) {
          markers->SetSample(f, m, p);
        } else {
          markers->SetMissing(f, m);
        }
      } else if (!finite && !p.array().isNaN().all()) {
        markers->SetMissing(f, m);  // Inf or a partly-NaN sample: missing, all NaN.
      }
    }
  }
}

Array MotionRotations(const Motion& motion) {
  const py::ssize_t frames = motion.num_frames();
  const py::ssize_t joints = frames > 0 ? static_cast<py::ssize_t>(motion.frames[0].rotations.size()) : 0;
  Array out({frames, joints, py::ssize_t{4}});
  auto r = out.mutable_unchecked<3>();
  for (py::ssize_t f = 0; f < frames; ++f) {
    for (py::ssize_t j = 0; j < joints; ++j) {
      const Eigen::Quaterniond& q = motion.frames[f].rotations[j];
      r(f, j, 0) = q.x();
      r(f, j, 1) = q.y();
      r(f, j, 2) = q.z();
      r(f, j, 3) = q.w();
    }
  }
  return out;
}

Array MotionTranslations(const Motion& motion) {
  const py::ssize_t frames = motion.num_frames();
  const py::ssize_t joints = frames > 0 ? static_cast<py::ssize_t>(motion.frames[0].translations.size()) : 0;
  Array out({frames, joints, py::ssize_t{3}});
  auto r = out.mutable_unchecked<3>();
  for (py::ssize_t f = 0; f < frames; ++f) {
    for (py::ssize_t j = 0; j < joints; ++j) {
      for (int k = 0; k < 3; ++k) r(f, j, k) = motion.frames[f].translations[j][k];
    }
  }
  return out;
}

Array RootTranslations(const Motion& motion) {
  const py::ssize_t frames = motion.num_frames();
  Array out({frames, py::ssize_t{3}});
  auto r = out.mutable_unchecked<2>();
  for (py::ssize_t f = 0; f < frames; ++f) {
    for (int k = 0; k < 3; ++k) {
      r(f, k) = motion.frames[f].translations.empty() ? 0.0 : motion.frames[f].translations[0][k];
    }
  }
  return out;
}

void CheckMotion(const Skeleton& skeleton, const Motion& motion) {
  ThrowIfError(ValidateMotion(skeleton, motion));
}

void CheckPose(const Skeleton& skeleton, const Pose& pose, const char* what) {
  ThrowIfError(ValidatePose(skeleton, pose, what));
}

void CheckFinite(const Array& array, const char* what) {
  const double* p = array.data();
  for (py::ssize_t i = 0; i < array.size(); ++i) {
    if (!std::isfinite(p[i])) throw py::value_error(std::string(what) + ": expected finite values");
  }
}

std::string BoundTypeName(const std::type_info& type) {
  const py::detail::type_info* info = py::detail::get_type_info(type);
  std::string name = info != nullptr ? info->type->tp_name : type.name();
  if (info == nullptr) py::detail::clean_type_id(name);
  return name.substr(name.rfind('.') + 1);  // "mocapsolve._core.Subject" -> "Subject".
}

void CheckShape(const Array& array, const std::vector<py::ssize_t>& shape, const char* what) {
  bool ok = array.ndim() == static_cast<py::ssize_t>(shape.size());
  for (size_t i = 0; ok && i < shape.size(); ++i) ok = shape[i] < 0 || array.shape(i) == shape[i];
  if (ok) return;
  std::string expected = "(";
  for (size_t i = 0; i < shape.size(); ++i) {
    expected += (i ? ", " : "") + (shape[i] < 0 ? std::string("n") : std::to_string(shape[i]));
  }
  std::string got = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) got += (i ? ", " : "") + std::to_string(array.shape(i));
  throw py::value_error(std::string(what) + ": expected shape " + expected + "), got " + got + ")");
}

Array ObservationsToArray(const std::vector<std::vector<Eigen::Vector3d>>& observed) {
  const py::ssize_t frames = static_cast<py::ssize_t>(observed.size());
  const py::ssize_t markers = frames > 0 ? static_cast<py::ssize_t>(observed[0].size()) : 0;
  Array out({frames, markers, py::ssize_t{3}});
  double* data = out.mutable_data();
  for (py::ssize_t f = 0; f < frames; ++f) {
    for (py::ssize_t m = 0; m < markers; ++m) {
      for (int k = 0; k < 3; ++k) *data++ = observed[f][m][k];
    }
  }
  return out;
}

std::vector<std::vector<Eigen::Vector3d>> ArrayToObservations(const Array& array) {
  CheckShape(array, {-1, -1, 3}, "observed");
  auto r = array.unchecked<3>();
  std::vector<std::vector<Eigen::Vector3d>> observed(array.shape(0));
  for (py::ssize_t f = 0; f < array.shape(0); ++f) {
    observed[f].resize(array.shape(1));
    for (py::ssize_t m = 0; m < array.shape(1); ++m) {
      Eigen::Vector3d p(r(f, m, 0), r(f, m, 1), r(f, m, 2));
      observed[f][m] = p.allFinite() ? p : Eigen::Vector3d::Constant(std::nan(""));
    }
  }
  return observed;
}

}  // namespace mocapsolve::python
