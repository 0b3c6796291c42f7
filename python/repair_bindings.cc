// Marker repair (thesis chapter 3): the repair settings (the CLI's flags) and repair().
#include "settings/corruption_settings.h"
#include "settings/repair_settings.h"
#include "problems/marker_repair/repair_evaluation.h"
#include "problems/marker_repair/marker_repair.h"
#include "python/bindings.h"
#include "python/keyword_docs.h"
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
  return RepairSettingOptions().Names() + "," + SolverOptions().Names();
}

}  // namespace

void BindRepair(py::module_& m) {
  py::class_<RepairSettings> settings(m, "RepairSettings",
      "Marker repair's options, one per flag of `mocapsolve repair` (same names, defaults and\n"
      "units: cm, degrees, frames). repair() takes them, and the SolverSettings, as keywords.");
  settings.def(py::init<>(), "Every option at the CLI's default.");
#define MOCAPSOLVE_FIELD(name) settings.def_readwrite(#name, &RepairSettings::name)
  MOCAPSOLVE_FIELD(dp_max_cm); MOCAPSOLVE_FIELD(dr_max_deg); MOCAPSOLVE_FIELD(outlier_cm);
  MOCAPSOLVE_FIELD(outliers); MOCAPSOLVE_FIELD(outlier_mads); MOCAPSOLVE_FIELD(outlier_min_cm);
  MOCAPSOLVE_FIELD(undo_swaps); MOCAPSOLVE_FIELD(swap_radius_cm); MOCAPSOLVE_FIELD(swap_min_frames);
  MOCAPSOLVE_FIELD(assign_unlabelled); MOCAPSOLVE_FIELD(unlabelled_min_cm); MOCAPSOLVE_FIELD(unlabelled_max_cm);
  MOCAPSOLVE_FIELD(unlabelled_min_frames);
  MOCAPSOLVE_FIELD(trim_max); MOCAPSOLVE_FIELD(small_track); MOCAPSOLVE_FIELD(small_gap);
  MOCAPSOLVE_FIELD(vel_clamp); MOCAPSOLVE_FIELD(edge_samples); MOCAPSOLVE_FIELD(fill); MOCAPSOLVE_FIELD(fill_samples); MOCAPSOLVE_FIELD(refit_reference); MOCAPSOLVE_FIELD(refit_rough_factor); MOCAPSOLVE_FIELD(rough_extension_factor); MOCAPSOLVE_FIELD(reference); MOCAPSOLVE_FIELD(reference_loss);
  MOCAPSOLVE_FIELD(reference_loss_cm); MOCAPSOLVE_FIELD(tracker_prior_weight);
  MOCAPSOLVE_FIELD(tracker_translation_prior); MOCAPSOLVE_FIELD(tracker_function_tolerance);
#undef MOCAPSOLVE_FIELD
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
        RepairSettings repair_settings;
        SolverSettings solver_settings = RepairSolverOptions().Defaults();
        ApplyKeywords(keywords,
                      {py::cast(&repair_settings, py::return_value_policy::reference),
                       py::cast(&solver_settings, py::return_value_policy::reference)},
                      RepairOptionNames());
        const Skeleton& skeleton = subject->skeleton;
        RepairOptions options;
        ThrowIfError(RepairOptionsFromSettings(repair_settings, solver_settings, skeleton, &options));
        const MarkerTakePtr take = TakeArgument(*subject, markers);
        SetRepairRestRotations(take->mean_pose, &options);  // As `mocapsolve repair`.
        std::vector<std::vector<Eigen::Vector3d>> repaired;
        Motion motion;
        RepairReport report;
        RepairIntermediates intermediates;
        auto out = std::make_shared<MarkerTrajectories>();
        int rewritten = 0;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RepairMarkers(skeleton, subject->markers, take->observed, take->unlabelled, options, &repaired,
                                 &motion, &report, &intermediates);
          if (status.ok()) {
            motion.frame_rate = take->trajectories.frame_rate;
            *out = WithRepairedSamples(*take, repaired, &rewritten, report.unlabelled);
          }
        }
        if (!status.ok()) {
          const std::string where = py::isinstance<py::str>(markers) ? std::string(py::str(markers)) + ": " : "";
          throw py::value_error(where + status.message());
        }
        const double mm = skeleton.unit().metres_per_unit * 1000.0;
        py::dict d;
        d["frames"] = static_cast<int>(take->observed.size());
        py::list swaps;
        for (const MarkerSwap& swap : report.swaps) {
          py::dict o;
          o["first_frame"] = swap.first;
          o["last_frame"] = swap.last;
          py::list renamed;
          for (const auto& [from, to] : swap.from_to) {
            renamed.append(py::make_tuple(subject->markers.label(from), subject->markers.label(to)));
          }
          o["markers_renamed_from_to"] = renamed;
          o["mean_distance_before_mm"] = swap.distance_before * mm;
          o["mean_distance_after_mm"] = swap.distance_after * mm;
          swaps.append(o);
        }
        d["swaps"] = swaps;
        py::list assigned;
        for (const UnlabelledAssignment& a : report.unlabelled) {
          py::dict o;
          o["marker"] = subject->markers.label(a.marker);
          o["unlabelled"] = take->unlabelled.names[a.track];
          o["first_frame"] = a.first;
          o["last_frame"] = a.last;
          o["frames"] = a.last - a.first + 1;
          o["mean_distance_mm"] = a.mean_distance * mm;
          assigned.append(o);
        }
        d["unlabelled_assigned"] = assigned;
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
      (std::string(R"doc(Finds broken marker intervals against a robust reference and refills them, as
`mocapsolve repair` (thesis chapter 3).

subject: a Subject; markers: a .c3d/.trc path or a Take.
Keywords: the repair options (RepairSettings: dp_max_cm=10, dr_max_deg=30, outlier_cm=4,
outliers='robust'|'fixed', outlier_mads=6, outlier_min_cm=1, undo_swaps=True,
swap_radius_cm=30, swap_min_frames=2, assign_unlabelled=True, unlabelled_min_cm=2,
unlabelled_max_cm=5, unlabelled_min_frames=3,
trim_max=120, small_track=120, small_gap=5, vel_clamp=0.25, edge_samples=1, fill='kriging'|'blend', fill_samples=10,
refit_reference=True, refit_rough_factor=3, rough_extension_factor=6,
reference='tracker'|'clip',
reference_loss='cauchy', reference_loss_cm=1, tracker_prior_weight=20,
tracker_translation_prior=0, tracker_function_tolerance=1e-4) and the solver options of
solve() (solver defaults to 'dls' here, as in the CLI).
Returns (markers, motion, report): the input file's markers with the repaired samples (its
own axes and unit: what --out_markers writes), the motion solved from them, and the
report as a dict ('swaps': {first_frame, last_frame, markers_renamed_from_to: [(from,
to)], mean_distance_before_mm, mean_distance_after_mm}; 'unlabelled_assigned': {marker,
unlabelled, first_frame, last_frame, frames, mean_distance_mm}; 'detected' and 'filled' lists of
{marker, first_frame, last_frame, what}, 'timings', 'rms_*_mm', 'repaired_observed'
(frames, set markers, 3) in skeleton units). Releases the GIL while repairing.)doc") +
       KeywordDefaults("Repair keywords and defaults (RepairSettings)", py::cast(RepairSettings()), RepairSettingOptions().Names()) + KeywordDefaults("Solver keywords and defaults (SolverSettings; solver 'dls' here)", py::cast(RepairSolverOptions().Defaults()), SolverOptions().Names())).c_str());

  py::class_<CorruptionSettings> damage(m, "CorruptionSettings",
      "The synthetic damage's options, one per flag of `mocapsolve corrupt`/`evaluate` (same\n"
      "names and defaults; distances in mm).");
  damage.def(py::init<>(), "Every option at the CLI's default.");
#define MOCAPSOLVE_FIELD(name) damage.def_readwrite(#name, &CorruptionSettings::name)
  MOCAPSOLVE_FIELD(corrupt_seed); MOCAPSOLVE_FIELD(gaps); MOCAPSOLVE_FIELD(gap_min); MOCAPSOLVE_FIELD(gap_max);
  MOCAPSOLVE_FIELD(cluster_gaps); MOCAPSOLVE_FIELD(cluster_radius_mm); MOCAPSOLVE_FIELD(fly_off_frames);
  MOCAPSOLVE_FIELD(fly_off_mm); MOCAPSOLVE_FIELD(swaps); MOCAPSOLVE_FIELD(swap_length);
  MOCAPSOLVE_FIELD(swap_radius_mm); MOCAPSOLVE_FIELD(noisy_markers); MOCAPSOLVE_FIELD(noise_length);
  MOCAPSOLVE_FIELD(noise_sigma_mm); MOCAPSOLVE_FIELD(swaps_in_gaps); MOCAPSOLVE_FIELD(jitter_markers);
  MOCAPSOLVE_FIELD(jitter_length); MOCAPSOLVE_FIELD(jitter_mm); MOCAPSOLVE_FIELD(ghosts);
  MOCAPSOLVE_FIELD(ghost_length); MOCAPSOLVE_FIELD(ghost_mm); MOCAPSOLVE_FIELD(unlabels);
  MOCAPSOLVE_FIELD(unlabel_length);
#undef MOCAPSOLVE_FIELD
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

  m.def("evaluate", [](SubjectPtr subject_arg, py::object markers, int trials, const py::kwargs& keywords) {
        const Subject* subject = &Required(subject_arg, "subject");
        RepairSettings repair_settings;
        SolverSettings solver_settings = RepairSolverOptions().Defaults();
        CorruptionSettings damage_settings;
        ApplyKeywords(keywords,
                      {py::cast(&repair_settings, py::return_value_policy::reference),
                       py::cast(&solver_settings, py::return_value_policy::reference),
                       py::cast(&damage_settings, py::return_value_policy::reference)},
                      RepairOptionNames() + "," + CorruptionSettingOptions().Names());
        if (trials < 1 || trials > 1000) throw py::value_error("--trials: expected 1..1000");
        const Skeleton& skeleton = subject->skeleton;
        RepairOptions options;
        ThrowIfError(RepairOptionsFromSettings(repair_settings, solver_settings, skeleton, &options));
        CorruptionOptions damage;
        ThrowIfError(CorruptionOptionsFromSettings(damage_settings, skeleton.unit(), &damage));
        const MarkerTakePtr take = TakeArgument(*subject, markers);
        SetRepairRestRotations(take->mean_pose, &options);  // As `mocapsolve evaluate`.
        const double cm = skeleton.unit().metres_per_unit * 100.0, mm = cm * 10.0;
        py::list out;
        for (int trial = 0; trial < trials; ++trial) {
          damage.seed = static_cast<uint32_t>(damage_settings.corrupt_seed + trial);
          std::vector<RepairEvaluationRow> rows;
          Status status = Status::Ok();
          {
            py::gil_scoped_release release;
            status = EvaluateRepairTrial(skeleton, subject->markers, take->observed, damage, options, &rows);
          }
          ThrowIfError(status);
          for (const RepairEvaluationRow& r : rows) {
            py::dict d;
            d["trial"] = trial;
            d["seed"] = damage.seed;
            d["method"] = r.method;
            d["joint_position_cm"] = r.joint_position_error * cm;
            d["joint_rotation_deg"] = r.joint_rotation_error * 180.0 / 3.14159265358979323846;
            d["marker_mean_mm"] = r.marker_error_mean * mm;
            d["marker_rms_mm"] = r.marker_error_rms * mm;
            d["marker_max_mm"] = r.marker_error_max * mm;
            d["damaged_samples"] = r.damaged_samples;
            d["covered_samples"] = r.covered_samples;
            d["velocity_jump_mm_per_frame"] = r.velocity_jump * mm;
            d["seconds"] = r.seconds;
            for (int k = 0; k < kNumDamageKinds; ++k) {
              const std::string kind = kDamageKindNames[k];
              d[(kind + "_mean_mm").c_str()] = r.kind_error[k] * mm;
              d[(kind + "_samples").c_str()] = r.kind_samples[k];
              d[(kind + "_recall").c_str()] = r.Recall(k);
            }
            d["precision"] = r.Precision();
            out.append(d);
          }
        }
        return out;
      }, py::arg("subject"), py::arg("markers"), py::kw_only(), py::arg("trials") = 1,
      (std::string(R"doc(The thesis' Table 1 on synthetic damage, as `mocapsolve evaluate`: per trial (seeds
corrupt_seed, corrupt_seed + 1, ...) the clean markers are damaged and refilled by every
method (original, polynomial, linear, PCA, reference only, ours). Keywords: the repair,
solver and corruption options. Returns one dict per trial and method, the columns of
evaluate's --table_csv (errors against the solve of the clean markers).
subject: a Subject; markers: a .c3d/.trc path or a Take; trials: how many damaged copies
(default 1, up to 1000).)doc") +
       KeywordDefaults("Repair keywords and defaults (RepairSettings)", py::cast(RepairSettings()), RepairSettingOptions().Names()) + KeywordDefaults("Solver keywords and defaults (SolverSettings; solver 'dls' here)", py::cast(RepairSolverOptions().Defaults()), SolverOptions().Names()) + KeywordDefaults("Damage keywords and defaults (CorruptionSettings)", py::cast(CorruptionSettings()), CorruptionSettingOptions().Names())).c_str());
}

}  // namespace mocapsolve::python
