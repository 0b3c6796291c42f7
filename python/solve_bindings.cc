// Marker solving: the solver settings (the CLI's flags), takes, per-frame and whole-clip
// solves through Ceres or DLS, and a frame-by-frame solver for Python loops.
#include <chrono>
#include <cmath>
#include <mutex>

#include "io/motion_file.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "settings/solver_settings.h"
#include "tasks/calibrate_task.h"
#include "problems/marker_solve/marker_clip_solver.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "problems/marker_solve/sequence_solver.h"
#include "settings/file_read_settings.h"
#include "settings/frame_limit_settings.h"
#include "python/bindings.h"
#include "python/keyword_docs.h"
#include "python/solve_bindings.h"
#include "tasks/solve_task.h"

namespace mocapsolve::python {

MarkerTakePtr TakeArgument(const Subject& subject, py::object markers) {
  if (py::isinstance<MarkerTake>(markers)) return markers.cast<MarkerTakePtr>();
  if (py::isinstance<MarkerTrajectories>(markers)) {  // What read_markers() and corrupt() return.
    MarkerTrajectories trajectories = markers.cast<const MarkerTrajectories&>();
    SyncMask(&trajectories);
    auto take = std::make_shared<MarkerTake>();
    ThrowIfError(TakeForSubject(subject, std::move(trajectories), "markers", take.get()));
    return take;
  }
  if (!py::isinstance<py::str>(markers) && !py::hasattr(markers, "__fspath__")) {
    throw py::type_error("markers: expected a Take, Markers or a .c3d/.trc path, got " +
                         std::string(py::str(markers.get_type().attr("__name__"))));
  }
  const std::string path = py::str(py::module_::import("os").attr("fspath")(markers));
  RequireReadable(path);
  auto take = std::make_shared<MarkerTake>();
  Status status = Status::Ok();
  {
    py::gil_scoped_release release;
    status = LoadTakeForSubject(subject, path, take.get());
  }
  ThrowIfError(status);
  return take;
}

MarkerTakePtr SolvableTakeArgument(const Subject& subject, py::object markers) {
  MarkerTakePtr take = TakeArgument(subject, markers);
  ThrowIfError(RequireTakeData(take->name, *take));
  return take;
}

SolverSettings SettingsFromKeywords(const py::kwargs& keywords) {
  SolverSettings settings;
  ApplyKeywords(keywords, {py::cast(&settings, py::return_value_policy::reference)}, SolverOptions().Names());
  return settings;
}

namespace {

// What FrameSolver.solve returns: the frame's report, its residual in mm under the name and
// unit solve()'s report uses (skeleton units, said so, when the skeleton's unit is unknown).
struct FrameSolveResult {
  FrameSolveReport report;
  LengthUnit unit;
  double rms_marker_residual() const {
    return unit.known() ? report.rms_marker_error * unit.metres_per_unit * 1000.0 : report.rms_marker_error;
  }
  std::string residual_unit() const { return unit.known() ? "mm" : "skeleton units"; }
};

// The per-frame solver of a subject, for loops in Python (the pose is updated in place).
class FrameSolver {
 public:
  FrameSolver(SubjectPtr subject, const py::kwargs& keywords) : subject_(std::move(subject)) {
    Required(subject_, "subject");
    settings_ = SettingsFromKeywords(keywords);
    ThrowIfError(MarkerSolveOptionsFromSettings(settings_, subject_->skeleton, subject_->mean_pose, &options_));
    solver_ = std::make_unique<MarkerFrameSolver>(subject_->skeleton, subject_->markers, options_);
  }

  // Threads sharing one solver take turns (MarkerFrameSolver keeps per-solve workspace);
  // the lock is taken with the GIL released, so other solvers and Python code run meanwhile.
  FrameSolveResult Solve(const Array& observed, Pose* pose_arg) {
    Pose& pose = Required(pose_arg, "pose");
    const std::vector<Eigen::Vector3d> frame = Frame(observed);
    CheckPoseShape(pose);
    FrameSolveResult result;
    result.unit = subject_->skeleton.unit();
    Status status = Status::Ok();
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      status = solver_->Solve(frame, &pose, &result.report);
    }
    ThrowIfError(status);
    return result;
  }

  Pose InitialPose(const Array& observed, bool root_from_markers) {
    const std::vector<Eigen::Vector3d> frame = Frame(observed);
    Pose pose = RestPose(subject_->skeleton);
    Status status = Status::Ok();
    {
      py::gil_scoped_release release;
      status = mocapsolve::InitialPose(subject_->skeleton, subject_->markers, frame, options_, &pose,
                                       root_from_markers);
    }
    ThrowIfError(status);
    return pose;
  }

  const SolverSettings& settings() const { return settings_; }

 private:
  // observed (markers, 3) as one frame's samples (non-finite = missing, as the solver reads).
  std::vector<Eigen::Vector3d> Frame(const Array& observed) const {
    CheckShape(observed, {subject_->markers.num_markers(), 3}, "observed");
    std::vector<Eigen::Vector3d> frame(subject_->markers.num_markers());
    const double* p = observed.data();
    for (auto& x : frame) {
      x = Eigen::Vector3d(p[0], p[1], p[2]);
      p += 3;
    }
    return frame;
  }

  // The warm start: the subject's joint count and finite unit rotations (a NaN pose would
  // come back NaN).
  void CheckPoseShape(const Pose& pose) const { CheckPose(subject_->skeleton, pose, "pose"); }

  SubjectPtr subject_;
  SolverSettings settings_;
  MarkerSolveOptions options_;
  std::unique_ptr<MarkerFrameSolver> solver_;
  std::mutex mutex_;  // Held (without the GIL) while solver_ solves.
};

}  // namespace

void BindSolve(py::module_& m) {
  py::class_<SolverSettings> settings(m, "SolverSettings",
      "The marker solver's options, one per flag of `mocapsolve solve` (same names, defaults\n"
      "and units). Keyword arguments of solve(), FrameSolver(), repair() set these.");
  settings.def(py::init<>(), "Every option at the CLI's default.");
  BindOptionFields(settings, SolverOptions());
  settings.def_readwrite("verbose", &SolverSettings::verbose);  // Not a declared option of this group.
  settings.def("validate", [](const SolverSettings& s, const std::string& skeleton_units) {
        MarkerSolveOptions frame;
        LengthUnit unit = LengthUnitFromName(skeleton_units);
        ThrowIfError(MarkerSolveOptionsFromSettings(s, unit, &frame));
        ClipSolveOptions clip;
        ThrowIfError(ClipSolveOptionsFromSettings(s, &clip));
      }, py::arg("skeleton_units") = "cm",
      "Raises ValueError (the CLI's message) if a value is invalid for a skeleton in\n"
      "skeleton_units (mm, cm, m, in; default cm: the prior and limit weights are in mm).");
  settings.def("as_dict", [](py::object self) {
        py::dict d;
        for (const Option& option : SolverOptions().options()) {
          const std::string& name = option.name;
          d[name.c_str()] = self.attr(name.c_str());
        }
        return d;
      }, "The settings by flag name (what `mocapsolve solve --print_config`-style files hold).");
  m.attr("SOLVER_OPTION_NAMES") = std::string(SolverOptions().Names());

  py::class_<MarkerTake, MarkerTakePtr>(m, "Take",
      "A marker file mapped onto a subject: .observed (frames, set markers, 3) in the skeleton's\n"
      "frame and units (NaN where missing), .markers (the file as read).")
      .def_property_readonly("observed", [](const MarkerTake& t) { return ObservationsToArray(t.observed); })
      .def_property_readonly("markers", [](const MarkerTake& t) { return std::make_shared<MarkerTrajectories>(t.trajectories); })
      .def_property_readonly("skeleton", [](const MarkerTake& t) { return std::make_shared<Skeleton>(t.skeleton); })
      .def_property_readonly("labels", [](const MarkerTake& t) {
        std::vector<std::string> labels;
        for (int i = 0; i < t.markers.num_markers(); ++i) labels.push_back(t.markers.label(i));
        return labels;
      }, "The marker set's labels, the order of observed's second axis.")
      .def_property_readonly("num_frames", [](const MarkerTake& t) { return static_cast<int>(t.observed.size()); })
      .def_property_readonly("rate", [](const MarkerTake& t) { return t.trajectories.frame_rate; });

  m.def("load_take", [](SubjectPtr subject_arg, py::object markers, const std::string& skeleton,
                        const std::string& markerset, const std::string& axes, double marker_scale,
                        const std::string& skeleton_units) {
        if (subject_arg == nullptr && !skeleton.empty() && !markerset.empty()) {
          RequireReadable(skeleton);
          RequireReadable(markerset);
          SubjectFiles files;  // As the CLI's --skeleton, --markerset, --axes, ... assemble one.
          files.skeleton_path = skeleton;
          files.markerset_path = markerset;
          files.axes = axes;
          files.marker_scale = marker_scale;
          files.skeleton_units = skeleton_units;
          subject_arg = std::make_shared<Subject>();
          ThrowIfError(LoadSubjectFromFiles(files, subject_arg.get()));
        }
        const Subject* subject = &Required(subject_arg, "subject");
        return TakeArgument(*subject, markers);
      }, py::arg("subject"), py::arg("markers"), py::kw_only(), py::arg("skeleton") = "", py::arg("markerset") = "",
      py::arg("axes") = DeclaredDefault(FileReadSettingOptions(), "axes"),
      py::arg("marker_scale") = DeclaredDefault(FileReadSettingOptions(), "marker_scale"),
      py::arg("skeleton_units") = DeclaredDefault(FileReadSettingOptions(), "skeleton_units"),
      "Reads markers (a .c3d/.trc path, or Markers) and maps them onto subject (label prefix,\n"
      "axes, scale): a Take with .observed (frames, markers, 3) in the skeleton's frame and units.\n"
      "subject: a Subject, or None with skeleton (.bvh/.asf path) and markerset (.json path) to\n"
      "assemble one as the CLI's flags do (axes: marker file -> skeleton axes; marker_scale:\n"
      "marker units -> skeleton units, 0 = from the units; skeleton_units: a BVH's unit).");

  m.def("solve", [](SubjectPtr subject_arg, py::object markers, int max_frames, const py::kwargs& keywords) {
        const Subject* subject = &Required(subject_arg, "subject");
        SolveConfig config;
        config.solver = SettingsFromKeywords(keywords);
        config.max_frames = max_frames;
        const MarkerTakePtr take = SolvableTakeArgument(*subject, markers);
        SolveResult result;
        Status status = Status::Ok();
        double seconds_in_cpp = 0.0;
        {
          py::gil_scoped_release release;
          const auto start = std::chrono::steady_clock::now();
          status = RunSolve(*take, config, SolveProgress(), &result);
          seconds_in_cpp = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        ThrowIfError(status);
        py::dict report = ReportToPython(result.report);
        report["seconds_in_cpp"] = seconds_in_cpp;  // The solve functions' own time (for overheads).
        const LengthUnit& unit = subject->skeleton.unit();
        const double scale = unit.known() ? unit.metres_per_unit * 1000.0 : 1.0;
        Array rms({static_cast<py::ssize_t>(result.per_frame.frame_rms.size())});
        for (size_t f = 0; f < result.per_frame.frame_rms.size(); ++f) {
          rms.mutable_at(f) = result.per_frame.frame_rms[f] * scale;
        }
        report["per_frame"]["frame_rms"] = rms;
        return py::make_tuple(std::move(result.motion), report);
      }, py::arg("subject"), py::arg("markers"), py::kw_only(),
      py::arg("max_frames") = DeclaredDefault(FrameLimitOption(), "max_frames"),
      (std::string(R"doc(Joint angles from markers, as `mocapsolve solve`.

subject: a Subject (read_subject or subject()); markers: a .c3d/.trc path or a Take.
max_frames: solve only the first N frames (0 = all).
Every other keyword is a solver option named like the CLI flag (SolverSettings), e.g.
  solver='dls'|'dls_generic'|'ceres', mode='frame'|'clip', linear_solver='dense_qr', max_iterations=50,
  function_tolerance=1e-6, gradient_tolerance=1e-10, parameter_tolerance=1e-8,
  num_threads=2 (clip), loss='none'|'huber'|'cauchy', loss_scale=1.0, marker_weight=1.0,
  prior_weight=20.0 (mm per radian), prior_translation_weight=0,
  rest_prior_weight=-1 (5 toward the subject's mean pose if it has one, else off),
  hidden_joint_prior_weight=100 (toward the mean pose, a joint whose own markers are all missing),
  hidden_twist_prior_weight=100 (toward the mean pose, a joint's twist about its one seen marker), limit_weight=0,
  smooth_order='velocity'|'acceleration', smooth_weight=1, smooth_translation_weight=0.1,
  clip_function_tolerance=1e-6, sparse_library='eigen_sparse', clip_solver='dls'|'dls_generic'|'ceres',
  dls_lambda=1e-3,
  dls_damping='adaptive'|'fixed'.
Returns (motion, report): the motion on the subject's skeleton and a dict with the CLI
report's figures ('per_frame': seconds, iterations, rms_marker_residual (mm), frame_rms
(frames,) array in mm, ...; 'clip' with mode='clip'). Releases the GIL while solving.
A bad option raises ValueError with the CLI's message; an unknown one TypeError.)doc") +
       KeywordDefaults("Solver keywords and defaults (SolverSettings)", py::cast(SolverSettings()), SolverOptions().Names())).c_str());

  py::class_<FrameSolveResult>(m, "FrameSolveReport", "One frame's solve.")
      .def_property_readonly("initial_cost", [](const FrameSolveResult& r) { return r.report.initial_cost; })
      .def_property_readonly("final_cost", [](const FrameSolveResult& r) { return r.report.final_cost; })
      .def_property_readonly("iterations", [](const FrameSolveResult& r) { return r.report.iterations; })
      .def_property_readonly("usable", [](const FrameSolveResult& r) { return r.report.usable; })
      .def_property_readonly("markers_used", [](const FrameSolveResult& r) { return r.report.markers_used; })
      .def_property_readonly("rms_marker_residual", &FrameSolveResult::rms_marker_residual,
                             "RMS marker residual in residual_unit (mm when the skeleton's unit is known), "
                             "as solve()'s report names it.")
      .def_property_readonly("residual_unit", &FrameSolveResult::residual_unit)
      .def_property_readonly("rms_marker_error", [](const FrameSolveResult& r) { return r.report.rms_marker_error; },
                             "The same in skeleton units (kept for older scripts).")
      .def_property_readonly("brief", [](const FrameSolveResult& r) { return r.report.brief; });

  py::class_<FrameSolver>(m, "FrameSolver",
      "One subject's per-frame marker solver (the one solve() runs over a take), for loops in\n"
      "Python: solver.solve(observed_frame, pose) updates pose in place.")
      .def(py::init<SubjectPtr, const py::kwargs&>(), py::arg("subject"),
           "A solver for subject (a Subject). Keywords: the solver options of solve() (mode and the\n"
           "clip options are ignored).")
      .def("solve", &FrameSolver::Solve, py::arg("observed"), py::arg("pose"),
           "observed: (markers, 3) in the skeleton's frame and units (Take.observed[f]), NaN =\n"
           "missing; pose: the warm start, overwritten with the solution (and, with a prior, the\n"
           "prior's reference). Returns a FrameSolveReport. Releases the GIL.")
      .def("initial_pose", &FrameSolver::InitialPose, py::arg("observed"), py::arg("root_from_markers") = false,
           "The first frame's start for observed (markers, 3): the best of the 24 axis-aligned root\n"
           "orientations (as solve()), or with root_from_markers=True the root pose from the\n"
           "markers' own geometry (as fit_skeleton).")
      .def_property_readonly("settings", &FrameSolver::settings);

  m.def("calibrate", [](const std::string& motion_path, const std::string& markers_path, py::object skeleton,
                        const std::string& axes, double marker_scale, int frame_offset, int min_valid_frames,
                        const std::string& attach, double amc_fps, const std::string& skeleton_units) {
        RequireReadable(motion_path);
        RequireReadable(markers_path);
        CalibrateSettings settings;
        settings.attach = attach;
        settings.frame_offset = frame_offset;
        settings.min_valid_frames = min_valid_frames;
        ThrowIfError(CheckCalibrateSettings(settings));
        MotionFileOptions motion_options;
        if (!skeleton.is_none()) motion_options.skeleton_path = py::str(skeleton);
        motion_options.skeleton_units = skeleton_units;
        motion_options.amc_frame_rate = amc_fps;
        SubjectCalibrationOptions options;
        options.axes = axes;
        options.marker_scale = marker_scale;
        options.skeleton_path = motion_options.skeleton_path.empty() ? motion_path : motion_options.skeleton_path;
        options.amc_fps = amc_fps;
        options.markers_name = markers_path;
        auto out = std::make_shared<CalibrateTaskResult>();
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          Skeleton model;
          Motion motion;
          MarkerTrajectories trajectories;
          status = ReadMotionFile(motion_path, motion_options, &model, &motion);
          if (status.ok()) status = ReadMarkerFile(markers_path, &trajectories);
          if (status.ok()) status = RunCalibrate(model, motion, trajectories, settings, options, out.get());
        }
        ThrowIfError(status);
        return py::make_tuple(std::make_shared<Subject>(std::move(out->calibration.subject)),
                              ReportToPython(out->report));
      }, py::arg("motion"), py::arg("markers"), py::kw_only(), py::arg("skeleton") = py::none(),
      py::arg("axes") = DeclaredDefault(FileReadSettingOptions(), "axes"),
      py::arg("marker_scale") = DeclaredDefault(FileReadSettingOptions(), "marker_scale"),
      py::arg("frame_offset") = CalibrateSettings().frame_offset,  // The declared defaults.
      py::arg("min_valid_frames") = CalibrateSettings().min_valid_frames, py::arg("attach") = CalibrateSettings().attach,
      py::arg("amc_fps") = DeclaredDefault(FileReadSettingOptions(), "amc_fps"),
      py::arg("skeleton_units") = DeclaredDefault(FileReadSettingOptions(), "skeleton_units"),
      R"doc(Calibrates a subject as `mocapsolve calibrate --out_subject`: where each marker sits
on the skeleton, from a solved motion (motion: .bvh, or .amc with skeleton= its .asf) and
the markers of the same take. axes: marker file -> skeleton axes ('y,z,x' for CMU C3D onto
ASF) or 'auto'; attach: 'auto' or a marker set .json whose joints are kept.
marker_scale: marker units -> skeleton units (0 = from the units); frame_offset: marker frame
= motion frame + frame_offset; min_valid_frames: markers valid in fewer matched frames are
left out (default 2); amc_fps: the .amc's frame rate (default 120); skeleton_units: the unit
of a skeleton that states none (mm, cm, m, in).
Returns (subject, report): the report of `calibrate --report` (after its file names): the
calibrated RMS, the axes, per-marker figures (joint, frames, rms, max_error, rms_mm).)doc");
}

}  // namespace mocapsolve::python
