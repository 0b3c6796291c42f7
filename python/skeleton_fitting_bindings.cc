// Skeleton fitting (`mocapsolve fit_skeleton`): FitSubjectToTake (tasks/fit_skeleton_task.h)
// with the command's options as keywords. The keyword list of the docstring is generated
// from the options' declarations (settings/skeleton_fit_settings.h).
#include <string>

#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "tasks/fit_skeleton_task.h"
#include "settings/solver_settings.h"
#include "settings/file_read_settings.h"
#include "python/bindings.h"
#include "python/keyword_docs.h"
#include "python/solve_bindings.h"

namespace mocapsolve::python {

void BindSkeletonFitting(py::module_& m) {
  py::class_<SkeletonFitSettings> settings(m, "SkeletonFitSettings",
      "The skeleton fit's options, one per flag of `mocapsolve fit_skeleton` (same names and\n"
      "defaults). fit_skeleton() takes them as keywords.");
  settings.def(py::init<>(), "Every option at the CLI's default.");
  BindOptionFields(settings, SkeletonFitSettingOptions());
  settings.def("validate", [](const SkeletonFitSettings& s) { ThrowIfError(ValidateSkeletonFitSettings(s)); },
               "Raises ValueError (the CLI's message) if a value is invalid.");
  m.attr("SKELETON_FIT_OPTION_NAMES") = SkeletonFitSettingOptions().Names();

  static const std::string doc =
      "Fits a subject (bone lengths, marker attachments and offsets) to a take's markers, as\n"
      "`mocapsolve fit_skeleton --out_subject` (tasks/fit_skeleton_task.h, the same code).\n\n"
      "markers: the take's .c3d/.trc path.\n"
      "template_subject: the template to start from, a Subject or a subject .json path; or\n"
      "  None with skeleton (.bvh/.asf path) and markerset (.json path) instead.\n"
      "skeleton, markerset: the template as files when template_subject is None.\n"
      "skeleton_units: the unit of a skeleton file that states none ('cm', 'm', ...).\n"
      "axes: the take's file axes -> skeleton axes ('y,z,x'), default 'x,y,z'.\n"
      "marker_scale: the take's units -> skeleton units; 0 (default) from the units.\n"
      "amc_fps: recorded in the fitted subject (default 120).\n"
      "progress: None, or a callable progress(event: dict) called (with the GIL) at each\n"
      "  round's start ('kind': 'round'), after each iteration ('iteration', with 'rms_mm'),\n"
      "  at each round's end ('round_done') and per frame of each pose solve ('frames',\n"
      "  with 'frames_done' of 'frames'), and once before the rounds when a template label\n"
      "  map is applied ('template_labels', 'text' its file); keys 'round', 'rounds',\n"
      "  'iteration', 'seconds'. When the fit runs again with the template's locked axes\n"
      "  freed (free_locked_axes: a foot's roll), 'freeing_axes' ('text' the joints) comes\n"
      "  first and that fit's rounds follow, numbered from 0 again.\n"
      "Keywords, the fit's options (SkeletonFitSettings):\n" +
      KeywordHelp(SkeletonFitSettingOptions().options(), py::cast(SkeletonFitSettings())) +
      "and the solver options of solve() (SolverSettings: solver='dls'|'dls_generic'|'ceres', max_iterations,\n"
      "prior_weight, ...).\n\n"
      "Returns (subject, motion, report): the fitted Subject (skeleton inline), the motion\n"
      "solved on it over the fitted frames, and the report dict of `--report` (rounds, kept\n"
      "round, rms_mm, bone scales, checks). With check='fail' (default) a subject that fails\n"
      "its checks raises ValueError with the CLI's message; 'warn' returns it (report\n"
      "['checks']['passed'] False). Bad options raise ValueError with the CLI's message, a\n"
      "missing file OSError. Releases the GIL while fitting.\n" +
      KeywordDefaults("Solver keywords and defaults (SolverSettings)", py::cast(SolverSettings()),
                      SolverOptions().Names());
  m.def("fit_skeleton", [](const std::string& markers, py::object template_subject, py::object skeleton,
                           py::object markerset, const std::string& skeleton_units, const std::string& axes,
                           double marker_scale, double amc_fps, py::object progress, const py::kwargs& keywords) {
        SkeletonFitSettings fit;
        SolverSettings solver;
        ApplyKeywords(keywords,
                      {py::cast(&fit, py::return_value_policy::reference),
                       py::cast(&solver, py::return_value_policy::reference)},
                      SkeletonFitSettingOptions().Names() + "," + SolverOptions().Names());
        ThrowIfError(ValidateSkeletonFitSettings(fit));
        SkeletonFitInputs inputs;
        inputs.markers_path = markers;
        inputs.axes = axes;
        inputs.marker_scale = marker_scale;
        inputs.amc_fps = amc_fps;
        ThrowIfError(CheckSkeletonFitInputsGiven(!template_subject.is_none(), !skeleton.is_none(),
                                                 !markerset.is_none(), !skeleton_units.empty(), true));
        if (!template_subject.is_none() && !py::isinstance<py::str>(template_subject)) {
          inputs.from_template_subject = true;
          inputs.templ = *template_subject.cast<SubjectPtr>();
          inputs.template_name = inputs.templ.name;
        } else {
          const std::string subject_path = template_subject.is_none() ? "" : std::string(py::str(template_subject));
          const std::string skeleton_path = skeleton.is_none() ? "" : std::string(py::str(skeleton));
          const std::string markerset_path = markerset.is_none() ? "" : std::string(py::str(markerset));
          for (const std::string& path : {subject_path, skeleton_path, markerset_path}) {
            if (!path.empty()) RequireReadable(path);
          }
          ThrowIfError(LoadSkeletonFitTemplate(subject_path, skeleton_path, markerset_path, skeleton_units, &inputs));
        }
        RequireReadable(markers);
        MarkerSolveOptions solve_options;
        ThrowIfError(MarkerSolveOptionsFromSettings(solver, inputs.templ.skeleton.unit(), &solve_options));
        SkeletonFitCallback callback;
        const double mm = inputs.templ.skeleton.unit().known()
                              ? inputs.templ.skeleton.unit().metres_per_unit * 1000.0 : 1.0;
        bool interrupted = false;
        if (!progress.is_none()) {
          callback = [&](const SkeletonFitEvent& e) {
            if (interrupted) return;
            const char* kind = nullptr;
            switch (e.kind) {
              case SkeletonFitEvent::kRoundStart: kind = "round"; break;
              case SkeletonFitEvent::kIteration: kind = "iteration"; break;
              case SkeletonFitEvent::kRoundDone: kind = "round_done"; break;
              case SkeletonFitEvent::kFrames: kind = "frames"; break;
              case SkeletonFitEvent::kTemplateLabels: kind = "template_labels"; break;
              case SkeletonFitEvent::kFreeingAxes: kind = "freeing_axes"; break;
              default: return;
            }
            py::gil_scoped_acquire acquire;
            py::dict d;
            d["kind"] = kind;
            d["round"] = e.round;
            d["rounds"] = e.rounds;
            d["iteration"] = e.iteration;
            d["iterations"] = e.iterations;
            d["frames"] = e.frames;
            d["frames_done"] = e.frames_done;
            d["markers"] = e.markers;
            d["rms_mm"] = e.rms * mm;
            d["seconds"] = e.seconds;
            d["text"] = e.text;  // template_labels: the map applied.
            try {
              progress(d);
            } catch (py::error_already_set& error) {
              // Reported after the fit: the library's callback cannot stop it.
              interrupted = true;
              error.restore();
            }
          };
        }
        auto result = std::make_shared<SkeletonFitResult>();
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = FitSubjectToTake(inputs, fit, solve_options, result.get(), callback);
        }
        if (interrupted) throw py::error_already_set();
        ThrowIfError(status);
        ThrowIfError(SkeletonFitCheckStatus(inputs, fit, *result));
        py::object report = ReportToPython(SkeletonFitReportJson(inputs, *result));
        return py::make_tuple(std::make_shared<Subject>(std::move(result->subject)), std::move(result->motion),
                              report);
      }, py::arg("markers"), py::arg("template_subject") = py::none(), py::kw_only(),
      py::arg("skeleton") = py::none(), py::arg("markerset") = py::none(),
      py::arg("skeleton_units") = DeclaredDefault(FileReadSettingOptions(), "skeleton_units"),
      py::arg("axes") = DeclaredDefault(FileReadSettingOptions(), "axes"),
      py::arg("marker_scale") = DeclaredDefault(FileReadSettingOptions(), "marker_scale"),
      py::arg("amc_fps") = DeclaredDefault(FileReadSettingOptions(), "amc_fps"),
      py::arg("progress") = py::none(), doc.c_str());
}

}  // namespace mocapsolve::python
