// Marker repair (thesis chapter 3): the repair and damage settings, repair(), evaluate() and corrupt().
#include "settings/corruption_settings.h"
#include "settings/repair_settings.h"
#include "problems/marker_repair/marker_repair.h"
#include "io/marker_file.h"
#include "settings/label_settings.h"
#include "settings/solver_settings.h"
#include "tasks/evaluate_task.h"
#include "tasks/label_task.h"
#include "tasks/repair_task.h"
#include "python/bindings.h"
#include "settings/method_settings.h"
#include "python/keyword_docs.h"
#include "python/solve_bindings.h"

namespace mocapsolve::python {
namespace {


std::string RepairOptionNames() {
  return RepairSettingOptions().Names() + "," + SolverOptions().Names();
}

}  // namespace

void BindRepair(py::module_& m) {
  py::class_<RepairSettings> settings(m, "RepairSettings",
      "Marker repair's options, one per flag of `mocapsolve repair` (same names, defaults and\n"
      "units: cm, degrees, frames). repair() takes them, and the SolverSettings, as keywords.");
  settings.def(py::init<>(), "Every option at the CLI's default.");
  BindOptionFields(settings, RepairSettingOptions());
  settings.def("validate", [](const RepairSettings& s, const SolverSettings& solver, const std::string& units) {
        JointSpec root;
        root.name = "root";
        Skeleton skeleton;
        ThrowIfError(Skeleton::Create({root}, {}, LengthUnitFromName(units), &skeleton));
        RepairOptions options;
        ThrowIfError(RepairOptionsFromSettings(s, solver, skeleton, &options));
      }, py::arg("solver") = SolverSettings(), py::arg("skeleton_units") = "cm",
      "Raises ValueError (the CLI's message) if a value, or one of the solver's (solver: a\n"
      "SolverSettings), is invalid for a skeleton in skeleton_units (mm, cm, m, in).");
  m.attr("REPAIR_OPTION_NAMES") = RepairSettingOptions().Names();

  m.def("repair", [](SubjectPtr subject_arg, py::object markers, const py::kwargs& keywords) {
        const Subject* subject = &Required(subject_arg, "subject");
        RepairConfig config;
        ApplyKeywords(keywords,
                      {py::cast(&config.repair, py::return_value_policy::reference),
                       py::cast(&config.solver, py::return_value_policy::reference)},
                      RepairOptionNames());
        const MarkerTakePtr take = SolvableTakeArgument(*subject, markers);
        RepairResult result;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunRepair(*take, config, nullptr, &result);
        }
        ThrowIfError(status);
        py::dict report = ReportToPython(result.report);
        report["repaired_observed"] = ObservationsToArray(result.repaired);
        return py::make_tuple(std::make_shared<MarkerTrajectories>(std::move(result.markers)), std::move(result.motion),
                              report);
      }, py::arg("subject"), py::arg("markers"),
      (std::string(R"doc(Finds broken marker intervals against a robust reference and refills them, as
`mocapsolve repair` (thesis chapter 3).

subject: a Subject; markers: a .c3d/.trc path or a Take.
Keywords: the repair options (RepairSettings) and the solver options of solve(), listed
below with their defaults.
Returns (markers, motion, report): the input file's markers with the repaired samples (its
own axes and unit: what --out_markers writes), the motion solved from them, and the
report as a dict, what `mocapsolve repair --report` writes ('swaps': {first_frame,
last_frame, markers_renamed_from_to: [{from, to}], mean_distance_before_mm,
mean_distance_after_mm}; 'unlabelled_assigned': {marker,
unlabelled, first_frame, last_frame, frames, mean_distance_mm}; 'detected' and 'filled' lists of
{marker, first_frame, last_frame, what}, 'timings', 'rms_*_mm', 'repaired_observed'
(frames, set markers, 3) in skeleton units). Releases the GIL while repairing.)doc") +
       KeywordDefaults("Repair keywords and defaults (RepairSettings)", py::cast(RepairSettings()), RepairSettingOptions().Names()) + KeywordDefaults("Solver keywords and defaults (SolverSettings)", py::cast(RepairSolverOptions().Defaults()), SolverOptions().Names())).c_str());

  py::class_<CorruptionSettings> damage(m, "CorruptionSettings",
      "The synthetic damage's options, one per flag of `mocapsolve corrupt`/`evaluate` (same\n"
      "names and defaults; distances in mm).");
  damage.def(py::init<>(), "Every option at the CLI's default.");
  BindOptionFields(damage, CorruptionSettingOptions());
  damage.def("validate", [](const CorruptionSettings& s, const std::string& units) {
        CorruptionOptions options;
        ThrowIfError(CorruptionOptionsFromSettings(s, LengthUnitFromName(units), &options));
      }, py::arg("units") = "mm",
      "Raises ValueError (the CLI's message) if a value is invalid for markers in units (mm, cm, m, in).");
  m.attr("CORRUPTION_OPTION_NAMES") = CorruptionSettingOptions().Names();

  m.def("corrupt", [](MarkerTrajectories& markers, const py::kwargs& keywords) {
        CorruptionSettings settings;
        ApplyKeywords(keywords, {py::cast(&settings, py::return_value_policy::reference)}, CorruptionSettingOptions().Names());
        CorruptionOptions options;
        ThrowIfError(CorruptionOptionsFromSettings(settings, markers.unit, &options));
        SyncMask(&markers);
        auto damaged = std::make_shared<MarkerTrajectories>(markers);
        CorruptionMask mask;
        {
          py::gil_scoped_release release;
          CorruptMarkers(options, damaged.get(), &mask);
        }
        py::array_t<std::int8_t> kinds({py::ssize_t{damaged->num_frames()}, py::ssize_t{damaged->num_markers()}});
        for (int f = 0; f < damaged->num_frames(); ++f) {
          for (int k = 0; k < damaged->num_markers(); ++k) {
            kinds.mutable_at(f, k) = static_cast<std::int8_t>(mask.empty() ? 0 : mask[f][k]);
          }
        }
        return py::make_tuple(damaged, kinds);
      }, py::arg("markers"),
      "Damages markers as `mocapsolve corrupt` (gaps, clustered occlusions, fly-offs, swaps,\n"
      "noise; keywords: the CorruptionSettings). Returns (damaged markers, (frames, markers)\n"
      "int8 mask of the damage kind per sample, 0 = untouched; signal/marker_corruption.h).");

  py::class_<EvaluateSettings> evaluate(m, "EvaluateSettings",
      "`mocapsolve evaluate`'s own options, one per flag (trials, white_noise_mm, protocol, refine_offsets,\n"
      "refine_prior_frames, off_body_mm; same defaults).");
  evaluate.def(py::init<>(), "Every option at the CLI's default.");
  evaluate.def_readwrite("trials", &EvaluateSettings::trials)
      .def_readwrite("white_noise_mm", &EvaluateSettings::white_noise_mm)
      .def_readwrite("protocol", &EvaluateSettings::protocol)
      .def_readwrite("refine_offsets", &EvaluateSettings::refine_offsets)
      .def_readwrite("refine_prior_frames", &EvaluateSettings::refine_prior_frames)
      .def_readwrite("off_body_mm", &EvaluateSettings::off_body_mm);
  m.def("evaluate", [](SubjectPtr subject_arg, py::object markers, const std::string& method,
                       const py::kwargs& keywords) {
        const Subject* subject = &Required(subject_arg, "subject");
        EvaluateConfig config;
        config.method = method;
        ApplyKeywords(keywords,
                      {py::cast(&config.evaluate, py::return_value_policy::reference),
                       py::cast(&config.repair, py::return_value_policy::reference),
                       py::cast(&config.solver, py::return_value_policy::reference),
                       py::cast(&config.damage, py::return_value_policy::reference),
                       py::cast(&config.fit, py::return_value_policy::reference)},
                      EvaluateSettingOptions().Names() + "," + RepairOptionNames() + "," +
                          CorruptionSettingOptions().Names() + "," + SkeletonFitSettingOptions().Names());
        const MarkerTakePtr take = SolvableTakeArgument(*subject, markers);
        EvaluateResult result;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunEvaluate(*take, config, nullptr, &result);
        }
        ThrowIfError(status);
        return ReportToPython(result.report);
      }, py::arg("subject"), py::arg("markers"), py::kw_only(), py::arg("method") = DefaultMethod(EvaluateMethodOption()),
      (std::string(R"doc(Scores marker repair on a take, as `mocapsolve evaluate`; returns the dict its --report
writes. method:
  'repair' (default): the thesis' Table 1 on synthetic damage: per trial (seeds
    seed, seed + 1, ...) the clean markers are damaged and refilled by
    every method (original, polynomial, linear, PCA, reference only, ours); 'methods'
    holds each method's mean over the trials, 'per_trial' one row per trial and method
    (the columns of --table_csv and more; errors against the solve of the clean markers);
  'leave_one_out': each marker predicted by the solve of the others ('per_marker', 'all'),
    under protocol='cross_take' (the subject from another take) or 'time_split' (fitted on
    the first half, the second scored; 'protocol' records which);
  'small_errors': recall and precision on 1-4 cm jumps and jitter ('seeds'), after
    white_noise_mm of noise.
subject: a Subject; markers: a .c3d/.trc path, Markers or a Take. Keywords: the evaluate
options (trials: how many damaged copies, default 1, up to 1000; white_noise_mm), the
repair, solver and corruption options, and fit_skeleton's (the fit of time_split's first half).
Releases the GIL.)doc") +
       KeywordDefaults("Evaluate keywords and defaults (EvaluateSettings)", py::cast(EvaluateSettings()),
                       EvaluateSettingOptions().Names()) +
       KeywordDefaults("Repair keywords and defaults (RepairSettings)", py::cast(RepairSettings()), RepairSettingOptions().Names()) + KeywordDefaults("Solver keywords and defaults (SolverSettings)", py::cast(EvaluateSolverOptions().Defaults()), SolverOptions().Names()) + KeywordDefaults("Damage keywords and defaults (CorruptionSettings)", py::cast(CorruptionSettings()), CorruptionSettingOptions().Names()) +
       KeywordDefaults("Fit keywords and defaults (SkeletonFitSettings)", py::cast(SkeletonFitSettings()),
                       SkeletonFitSettingOptions().Names())).c_str());
  py::class_<LabelSettings> label_settings(m, "LabelSettings",
                                           "How label() finds the body and tracks the points (the CLI's label flags).");
  label_settings.def(py::init<>(), "Every option at the CLI's default.");
  BindOptionFields(label_settings, LabelSettingOptions());
  m.def("label", [](SubjectPtr subject_arg, py::object markers, const py::kwargs& keywords) {
        const Subject& subject = Required(subject_arg, "subject");
        LabelConfig config;
        ApplyKeywords(keywords,
                      {py::cast(&config.label, py::return_value_policy::reference),
                       py::cast(&config.solver, py::return_value_policy::reference)},
                      LabelSettingOptions().Names() + "," + RepairSolverOptions().Names());
        MarkerTrajectories file;
        std::string name = "markers";
        if (py::isinstance<MarkerTrajectories>(markers)) {  // What read_markers() and corrupt() return.
          file = markers.cast<const MarkerTrajectories&>();
          SyncMask(&file);
        } else {
          if (!py::isinstance<py::str>(markers) && !py::hasattr(markers, "__fspath__")) {
            throw py::type_error("markers: expected Markers or a .c3d/.trc path, got " +
                                 std::string(py::str(markers.get_type().attr("__name__"))));
          }
          name = py::str(py::module_::import("os").attr("fspath")(markers));
          RequireReadable(name);
          ThrowIfError(ReadMarkerFile(name, &file));
        }
        LabelResult result;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunLabel(subject, file, name, config, nullptr, &result);
        }
        ThrowIfError(status);
        return py::make_tuple(std::make_shared<MarkerTrajectories>(std::move(result.markers)),
                              ReportToPython(result.report));
      }, py::arg("subject"), py::arg("markers"),
      (std::string(R"doc(Names the points of a raw, unlabelled take with the subject's markers, as
`mocapsolve label` (labels the file carries are ignored: points in any order, ghosts,
dropouts). subject: a Subject; markers: a .c3d/.trc path or Markers.
Returns (markers, report): one column per marker of the subject, then the points left
unlabelled as '*1', '*2', ... (samples as the file holds them), and the report as a dict,
what `mocapsolve label --report` writes. Releases the GIL.
Keywords (LabelSettings) and the solver options of solve():
)doc") + KeywordHelp(LabelSettingOptions().options(), py::cast(LabelSettings()))).c_str());
}

}  // namespace mocapsolve::python
