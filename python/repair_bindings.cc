// Marker repair (thesis chapter 3): the repair settings (the CLI's flags) and repair().
#include "pipeline/repair_settings.h"
#include "problems/marker_repair/marker_repair.h"
#include "python/bindings.h"
#include "python/solve_bindings.h"

namespace mocapsolve::python {
namespace {

py::list IntervalList(const std::vector<RepairInterval>& intervals, const MarkerSet& markers) {
  py::list list;
  for (const RepairInterval& i : intervals) {
    py::dict d;
    d["marker"] = markers.label(i.marker);
    d["marker_index"] = i.marker;
    d["first_frame"] = i.first;
    d["last_frame"] = i.last;
    d["what"] = i.what;
    list.append(d);
  }
  return list;
}

std::string RepairOptionNames() {
  return std::string(kRepairSettingNames) + "," + kSolverSettingNames;
}

}  // namespace

void BindRepair(py::module_& m) {
  py::class_<RepairSettings> settings(m, "RepairSettings",
      "Marker repair's options, one per flag of `mocapsolve repair` (same names, defaults and\n"
      "units: cm, degrees, frames). repair() takes them, and the SolverSettings, as keywords.");
  settings.def(py::init<>());
#define MOCAPSOLVE_FIELD(name) settings.def_readwrite(#name, &RepairSettings::name)
  MOCAPSOLVE_FIELD(dp_max_cm); MOCAPSOLVE_FIELD(dr_max_deg); MOCAPSOLVE_FIELD(outlier_cm);
  MOCAPSOLVE_FIELD(trim_max); MOCAPSOLVE_FIELD(small_track); MOCAPSOLVE_FIELD(small_gap);
  MOCAPSOLVE_FIELD(vel_clamp); MOCAPSOLVE_FIELD(reference); MOCAPSOLVE_FIELD(reference_loss);
  MOCAPSOLVE_FIELD(reference_loss_cm); MOCAPSOLVE_FIELD(tracker_prior_weight);
  MOCAPSOLVE_FIELD(tracker_translation_prior); MOCAPSOLVE_FIELD(tracker_function_tolerance);
#undef MOCAPSOLVE_FIELD
  m.attr("REPAIR_OPTION_NAMES") = std::string(kRepairSettingNames);

  m.def("repair", [](SubjectPtr subject, py::object markers, const py::kwargs& keywords) {
        RepairSettings repair_settings;
        SolverSettings solver_settings;
        solver_settings.solver = kRepairDefaultSolver;
        ApplyKeywords(keywords,
                      {py::cast(&repair_settings, py::return_value_policy::reference),
                       py::cast(&solver_settings, py::return_value_policy::reference)},
                      RepairOptionNames());
        const Skeleton& skeleton = subject->skeleton;
        RepairOptions options;
        ThrowIfError(RepairOptionsFromSettings(repair_settings, solver_settings, skeleton, &options));
        const MarkerTakePtr take = TakeArgument(*subject, markers);
        std::vector<std::vector<Eigen::Vector3d>> repaired;
        Motion motion;
        RepairReport report;
        RepairIntermediates intermediates;
        auto out = std::make_shared<MarkerTrajectories>();
        int rewritten = 0;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RepairMarkers(skeleton, subject->markers, take->observed, options, &repaired, &motion,
                                 &report, &intermediates);
          if (status.ok()) {
            motion.frame_rate = take->trajectories.frame_rate;
            *out = WithRepairedSamples(*take, repaired, &rewritten);
          }
        }
        if (!status.ok()) {
          const std::string where = py::isinstance<py::str>(markers) ? std::string(py::str(markers)) + ": " : "";
          throw py::value_error(where + status.message());
        }
        const double mm = skeleton.unit().metres_per_unit * 1000.0;
        py::dict d;
        d["frames"] = static_cast<int>(take->observed.size());
        d["detected"] = IntervalList(report.detected, subject->markers);
        d["filled"] = IntervalList(report.filled, subject->markers);
        py::list timings;
        for (const RepairStageTime& t : report.timings) {
          py::dict o;
          o["stage"] = t.stage;
          o["seconds"] = t.seconds;
          timings.append(o);
        }
        d["timings"] = timings;
        d["rms_naive_mm"] = report.naive_rms * mm;
        d["rms_reference_mm"] = report.reference_rms * mm;
        d["rms_repaired_mm"] = report.repaired_rms * mm;
        d["resolved_frames"] = report.resolved_frames;
        d["reference"] = repair_settings.reference;
        d["trimmed_samples"] = report.trimmed_samples;
        d["removed_track_samples"] = report.removed_track_samples;
        d["polynomial_samples"] = report.polynomial_samples;
        d["rewritten_samples"] = rewritten;
        d["repaired_observed"] = ObservationsToArray(repaired);
        return py::make_tuple(out, std::move(motion), d);
      }, py::arg("subject"), py::arg("markers"),
      R"doc(Finds broken marker intervals against a robust reference and refills them, as
`mocapsolve repair` (thesis chapter 3).

subject: a Subject; markers: a .c3d/.trc path or a Take.
Keywords: the repair options (RepairSettings: dp_max_cm=10, dr_max_deg=30, outlier_cm=4,
trim_max=120, small_track=120, small_gap=5, vel_clamp=0.25, reference='tracker'|'clip',
reference_loss='cauchy', reference_loss_cm=1, tracker_prior_weight=20,
tracker_translation_prior=0, tracker_function_tolerance=1e-4) and the solver options of
solve() (solver defaults to 'dls' here, as in the CLI).
Returns (markers, motion, report): the input file's markers with the repaired samples (its
own axes and unit: what --out_markers writes), the motion solved from them, and the
report as a dict ('detected' and 'filled' lists of {marker, first_frame, last_frame,
what}, 'timings', 'rms_*_mm', 'repaired_observed' (frames, set markers, 3) in skeleton
units). Releases the GIL while repairing.)doc");
}

}  // namespace mocapsolve::python
