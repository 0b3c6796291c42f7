// The pipeline on one take (pipeline/take_pipeline.h): repair and solve, optional
// filtering, retargeting onto each character, the quality gate; outputs optionally written.
// And batch(): the pipeline over many takes in worker processes (tasks/batch_task.h); view():
// a take, motions and characters as one browser page (tasks/view_task.h).
#include <cstdlib>

#include "batch/batch_summary.h"
#include "batch/worker_process.h"
#include "io/atomic_file.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "settings/memory_settings.h"
#include "settings/repair_settings.h"
#include "pipeline/quality_gate.h"
#include "settings/retarget_settings.h"
#include "pipeline/take_pipeline.h"
#include "settings/delivery_settings.h"
#include "settings/pyramid_settings.h"
#include "settings/file_read_settings.h"
#include "settings/retarget_run_settings.h"
#include "settings/skeleton_fit_settings.h"
#include "settings/label_settings.h"
#include "settings/take_settings.h"
#include "settings/view_settings.h"
#include "python/bindings.h"
#include "python/keyword_docs.h"
#include "tasks/auto_subject_task.h"
#include "tasks/batch_task.h"
#include "tasks/view_task.h"

namespace mocapsolve::python {
namespace {

// The CLI the batch's workers run: `executable`, else $MOCAPSOLVE_CLI, else `mocapsolve` on
// PATH, else the build tree's (build/bin/mocapsolve beside build/python/mocapsolve/).
std::string BatchExecutable(const std::string& executable) {
  if (!executable.empty()) return executable;
  if (const char* cli = std::getenv("MOCAPSOLVE_CLI"); cli != nullptr && *cli != 0) return cli;
  const py::object on_path = py::module_::import("shutil").attr("which")("mocapsolve");
  if (!on_path.is_none()) return py::str(on_path);
  const py::module_ os_path = py::module_::import("os.path");
  const py::object package = os_path.attr("dirname")(py::module_::import("mocapsolve").attr("__file__"));
  const std::string built = py::str(os_path.attr("join")(package, "..", "..", "bin", "mocapsolve"));
  if (py::bool_(os_path.attr("exists")(built))) return built;
  throw py::value_error("batch: no mocapsolve executable for the workers: pass executable=, set MOCAPSOLVE_CLI "
                        "or put mocapsolve on PATH");
}

// Its version, as its --version prints it ("mocapsolve 0.1.0"): part of every take's key.
std::string ExecutableVersion(const std::string& executable) {
  std::string text;
  ThrowIfError(RunAndCapture({executable, "--version"}, &text));
  const std::string prefix = "mocapsolve ";
  if (text.compare(0, prefix.size(), prefix) != 0) {
    throw py::value_error(executable + ": not a mocapsolve executable (--version printed '" + text + "')");
  }
  return text.substr(prefix.size(), text.find_first_of("\r\n") - prefix.size());
}

}  // namespace

void BindPipeline(py::module_& m) {
  py::class_<QualityGate> gate(m, "QualityGate",
      "The pipeline's quality gate thresholds, one per flag of `mocapsolve pipeline` (gate_*:\n"
      "same names, defaults and units; 0 turns a check off). pipeline() takes them as keywords.");
  gate.def(py::init<>(), "Every threshold at the CLI's default.");
  BindOptionFields(gate, QualityGateOptions());  // gate_naive_rms_mm, ..., gate_limb_vertices.
  py::class_<MemorySettings> memory(m, "MemorySettings",
      "The memory a run may take (memory_mb, MB; 0 = no limit), as `mocapsolve pipeline --memory_mb`:\n"
      "pipeline() takes it as a keyword and refuses, before any work, a take whose estimate is over it.");
  memory.def(py::init<>(), "No limit, the CLI's default.");
  BindOptionFields(memory, MemoryOption());
  py::class_<DeliverySettings> delivery(m, "DeliverySettings",
      "Which files a take is delivered as, one per flag of `mocapsolve pipeline`/`batch` (same\n"
      "names and defaults: formats='glb', a comma-separated list of glb, fbx, bvh; out_fps;\n"
      "frames and seconds, 'A:B' ranges; fbx_key_tolerance, mm). pipeline()\n"
      "and batch() take them as keywords.");
  delivery.def(py::init<>(), "Every option at the CLI's default.");
  BindOptionFields(delivery, DeliverySettingOptions());  // formats, out_fps, frames, ...
  delivery.def("validate", [](const DeliverySettings& s) {
        ClipDelivery checked;
        ThrowIfError(ClipDeliveryFromSettings(s, &checked));
      },
               "Raises ValueError (the CLI's message) if a value is invalid.");
  m.attr("DELIVERY_OPTION_NAMES") = DeliverySettingOptions().Names();
  m.def("pipeline", [](py::object subject_arg, const std::string& markers, const std::vector<std::string>& characters,
                       const std::string& out_dir, const std::string& take_name, int filter_levels,
                       const std::string& label, double kernel_a,
                       double tension, bool animation_only, const std::string& view, const py::kwargs& keywords) {
        const bool auto_subject = subject_arg.is_none() || (py::isinstance<py::str>(subject_arg) &&
                                                            std::string(py::str(subject_arg)) == kAutoSubject);
        if (py::isinstance<py::str>(subject_arg) && !auto_subject) {
          throw py::value_error("subject: a Subject (read_subject), 'auto' or None, got '" +
                                std::string(py::str(subject_arg)) + "'");
        }
        RepairSettings repair_settings;
        SolverSettings solver_settings = RepairSolverOptions().Defaults();
        RetargetSettings retarget_settings;
        QualityGate gate_settings;
        DeliverySettings delivery_settings;
        LabelSettings label_settings;
        SkeletonFitSettings fit_settings = AutoSubjectFitOptions().Defaults();
        MemorySettings memory_settings;
        ApplyKeywords(keywords,
                      {py::cast(&repair_settings, py::return_value_policy::reference),
                       py::cast(&solver_settings, py::return_value_policy::reference),
                       py::cast(&retarget_settings, py::return_value_policy::reference),
                       py::cast(&gate_settings, py::return_value_policy::reference),
                       py::cast(&delivery_settings, py::return_value_policy::reference),
                       py::cast(&label_settings, py::return_value_policy::reference),
                       py::cast(&fit_settings, py::return_value_policy::reference),
                       py::cast(&memory_settings, py::return_value_policy::reference)},
                      RepairSettingOptions().Names() + "," + SolverOptions().Names() + "," +
                          RetargetSettingOptions().Names() + ",foot_joints," + QualityGateOptions().Names() + "," +
                          DeliverySettingOptions().Names() + "," + LabelSettingOptions().Names() + "," +
                          AutoSubjectFitOptions().Names() + "," + MemoryOption().Names());
        ThrowIfError(QualityGateOptions().Validate(gate_settings));
        ThrowIfError(ValidateSkeletonFitSettings(fit_settings));
        CharacterFileOptions character_files;
        ThrowIfError(CharacterFilesFromSettings(delivery_settings, animation_only, &character_files));
        if (!IsMarkerFile(markers)) throw py::value_error(markers + ": expected a .c3d or .trc");
        RequireReadable(markers);
        for (const std::string& path : characters) RequireReadable(path);
        // subject='auto' (or None): fitted from the take first (tasks/auto_subject_task.h).
        std::unique_ptr<AutoSubjectResult> fitted;
        if (auto_subject) {
          fitted = std::make_unique<AutoSubjectResult>();
          Status fit_status = Status::Ok();
          {
            py::gil_scoped_release release;
            fit_status = FitAutoSubject(markers, fit_settings, solver_settings, fitted.get());
          }
          ThrowIfError(fit_status);
        }
        const Subject* subject = fitted ? &fitted->fit.subject : &Required(subject_arg.cast<SubjectPtr>(), "subject");
        TakePipelineOptions options;
        ThrowIfError(RepairOptionsFromSettings(repair_settings, solver_settings, subject->skeleton, &options.repair));
        retarget_settings.solver = solver_settings.solver;
        retarget_settings.limit_weight = solver_settings.limit_weight;
        ThrowIfError(RetargetOptionsFromSettings(retarget_settings, &options.retarget));
        options.filter_levels = filter_levels;
        ThrowIfError(TakeSettingOptions().Validate(TakeSettings{take_name, filter_levels, label}));
        options.label = label;
        options.labelling = label_settings;
        options.label_solver = solver_settings;
        ThrowIfError(PyramidOptionsFromSettings(PyramidSettings{kernel_a, tension}, filter_levels, &options.filter));
        options.gate = gate_settings;
        options.memory_mb = memory_settings.memory_mb;
        ThrowIfError(ClipDeliveryFromSettings(delivery_settings, &options.delivery));
        std::string error;
        if (!options.IsValid(&error)) throw py::value_error(error);
        std::string view_path, warning;
        if (!out_dir.empty()) ThrowIfError(TakeViewPath(view, out_dir, &view_path, &warning));
        if (!warning.empty()) py::module_::import("warnings").attr("warn")("pipeline: " + warning);
        TakeInputs inputs;
        inputs.name = take_name.empty() ? FileStem(markers) : take_name;
        inputs.subject = subject;
        inputs.markers_path = markers;
        inputs.character_paths = characters;
        inputs.subject_from_take = fitted != nullptr;
        if (!out_dir.empty()) ThrowIfError(CheckCharacterFiles(out_dir, inputs, character_files));
        auto result = std::make_shared<TakeResult>();
        JsonObject report;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunTakePipeline(inputs, options, result.get());
          if (status.ok()) {
            report = TakeReport(inputs, *result);
            if (fitted) report.Add("subject_fit", AutoSubjectReport(*fitted));
            const bool in_take_folder = view_path == ViewPagePath(out_dir);
            report.Add("view", view_path.empty() ? JsonValue() : JsonValue(in_take_folder ? "view.html" : view_path));
            if (!out_dir.empty()) {
              status = MakeFolders(out_dir);
              if (status.ok() && fitted) status = WriteSubject(AutoSubjectPath(out_dir), fitted->fit.subject);
              if (status.ok()) status = WriteTakeOutputs(out_dir, inputs, *result, report, view_path, character_files);
            }
          }
        }
        ThrowIfError(status);
        py::dict out;
        out["solved"] = result->solved.ToMotion();
        out["repaired_markers"] = std::make_shared<MarkerTrajectories>(result->repaired_file);
        py::dict retargeted;
        for (const CharacterOutput& c : result->characters) retargeted[c.name.c_str()] = c.delivered_motion();
        out["characters"] = retargeted;
        out["passed"] = result->verdict.pass;
        out["failures"] = result->verdict.failures;
        out["report"] = ReportToPython(report);
        out["subject"] = fitted ? std::make_shared<Subject>(fitted->fit.subject) : subject_arg.cast<SubjectPtr>();
        return out;
      }, py::arg("subject"), py::arg("markers"), py::kw_only(), py::arg("characters") = std::vector<std::string>(),
      py::arg("out_dir") = "", py::arg("take_name") = DeclaredDefault(TakeSettingOptions(), "take_name"),
      py::arg("filter_levels") = DeclaredDefault(TakeSettingOptions(), "filter_levels"),
      py::arg("label") = DeclaredDefault(TakeSettingOptions(), "label"),
      py::arg("kernel_a") = PyramidSettings().kernel_a,
      py::arg("tension") = PyramidSettings().tension, py::arg("animation_only") = DeclaredDefault(RetargetRunSettingOptions(), "animation_only"),
      py::arg("view") = "auto",
      (std::string(R"doc(One take end to end, as `mocapsolve pipeline`: repair and solve the markers (a .c3d/.trc
path) of the subject (a Subject; or 'auto' or None: fitted from the take first, as the CLI's
--subject=auto, with the fit_skeleton keywords, fit_max_frames=600 by default; a subject
that fails its checks raises ValueError; out_dir then also gets subject.json and the report
'subject_fit'), filter (filter_levels > 0), retarget onto each character (.glb
paths), check the quality gate (the gate_* keywords, a QualityGate: see below).
take_name: the take's name in the report ('' = the marker file's stem).
filter_levels: the multiresolution filter's levels (0 = off), with kernel_a (the Cardinal
spline kernel's a, default 0.4) and tension (default 0).
label: 'auto' (default) labels the take's points first, as label() does, when the file
lacks some of the subject's labels (a raw capture); 'always'; 'never'. The label options
(gate, min_confidence, ...; LabelSettings) are keywords too.
Keywords: the repair, solver, retarget, quality gate, delivery and label options.
out_dir: also write repaired markers, solved.bvh, <character>.glb and report.json there,
and the take's page: view='auto' (default) DIR/view.html when the viewer's runtime is
installed (else a warning), 'off' none, or a PAGE.html path (the runtime then required);
formats='glb,fbx,bvh' also writes <character>.fbx (binary FBX) and <character>.bvh;
frames='A:B' / seconds='A:B' and out_fps cut and resample the take in the character files
(and in 'characters' below);
animation_only: each <character>.glb and .fbx then holds the character's skeleton, skin
and the take only, no meshes (as the CLI's --animation_only).
Returns a dict: 'solved' (Motion), 'repaired_markers' (Markers), 'characters' {name:
Motion}, 'subject' (the Subject used), 'passed', 'failures', 'report' (the report.json contents). Releases the GIL.)doc") +
       KeywordDefaults("Repair keywords and defaults (RepairSettings)", py::cast(RepairSettings()), RepairSettingOptions().Names()) + KeywordDefaults("Solver keywords and defaults (SolverSettings)", py::cast(RepairSolverOptions().Defaults()), SolverOptions().Names()) + KeywordDefaults("Retarget keywords and defaults (RetargetSettings)", py::cast(RetargetSettings()), RetargetSettingOptions().Names() + ",foot_joints") +
       KeywordDefaults("Quality gate keywords and defaults (QualityGate; 0 turns a check off)", py::cast(QualityGate()),
                       QualityGateOptions().Names()) +
       KeywordDefaults("Delivery keywords and defaults (DeliverySettings)", py::cast(DeliverySettings()),
                       DeliverySettingOptions().Names())).c_str());

  m.def("batch", [](const std::string& manifest, const std::string& markers_glob, const std::string& subject,
                    const std::vector<std::string>& characters, const std::string& out_dir,
                    const std::string& write_manifest, int jobs, int take_threads, double take_timeout,
                    int take_memory_mb, bool force, bool retry_failed, bool merge, const std::string& shard,
                    const std::string& executable, const py::kwargs& keywords) {
        DeliverySettings delivery_settings;
        ApplyKeywords(keywords, {py::cast(&delivery_settings, py::return_value_policy::reference)},
                      DeliverySettingOptions().Names());
        ClipDelivery checked;
        ThrowIfError(ClipDeliveryFromSettings(delivery_settings, &checked));
        JsonObject given;  // The delivery keywords given: every take's (tasks/batch_task.h).
        for (const Option& option : DeliverySettingOptions().options()) {
          if (!keywords.contains(option.name)) continue;
          const std::string text = DeliverySettingOptions().Get(option.name, delivery_settings);
          if (option.type == OptionType::kString) {
            given.Add(option.name, text);
          } else if (option.type == OptionType::kBool) {
            given.Add(option.name, text == "true");
          } else {
            given.Add(option.name, JsonValue(std::stod(text)));
          }
        }
        BatchInputs inputs;
        inputs.pipeline_options = keywords.empty() ? "" : given.ToString(/*indent=*/false);
        inputs.manifest = manifest;
        inputs.markers_glob = markers_glob;
        inputs.subject = subject;
        inputs.characters = characters;
        inputs.out_dir = out_dir;
        inputs.write_manifest = write_manifest;
        inputs.settings.jobs = jobs;
        inputs.settings.take_threads = take_threads;
        inputs.settings.take_timeout = take_timeout;
        inputs.settings.take_memory_mb = take_memory_mb;
        inputs.settings.force = force;
        inputs.settings.retry_failed = retry_failed;
        inputs.settings.merge = merge;
        inputs.settings.shard = shard;
        inputs.executable = BatchExecutable(executable);
        inputs.version = ExecutableVersion(inputs.executable);
        BatchTaskResult task;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunBatchTask(inputs, nullptr, &task);
        }
        ThrowIfError(status);
        py::dict out;
        const char* kinds[] = {"ran", "merged", "manifest_only", "empty_shard"};
        out["kind"] = kinds[static_cast<int>(task.kind)];
        out["done"] = task.result.done;
        out["failed"] = task.result.failed;
        out["summary"] = py::module_::import("json").attr("loads")(FormatSummaryJson(task.result, inputs.version));
        out["summary_base"] = task.summary_base;
        return out;
      }, py::kw_only(), py::arg("manifest") = "", py::arg("markers_glob") = "", py::arg("subject") = "",
      py::arg("characters") = std::vector<std::string>(), py::arg("out_dir") = "", py::arg("write_manifest") = "",
      // The declared defaults (settings/batch_settings.h).
      py::arg("jobs") = BatchSettings().jobs, py::arg("take_threads") = BatchSettings().take_threads,
      py::arg("take_timeout") = BatchSettings().take_timeout, py::arg("take_memory_mb") = BatchSettings().take_memory_mb,
      py::arg("force") = BatchSettings().force, py::arg("retry_failed") = BatchSettings().retry_failed,
      py::arg("merge") = BatchSettings().merge, py::arg("shard") = BatchSettings().shard,
      py::arg("executable") = "",
      R"doc(Many takes through the pipeline, as `mocapsolve batch` (the same task): each take in
its own worker process running `executable pipeline`, resumable (a take whose key of
inputs, options and version matches is skipped).

manifest: a batch manifest (.json; docs/batch.md), or markers_glob: one take per matching
marker file (quote nothing: a pattern string) with subject (a subject .json path) and
characters (.glb paths). out_dir: where each take's folder and summary.json/.csv go.
write_manifest: also write the batch's manifest there (alone: without out_dir).
jobs: takes at once (0 = the cores); take_threads: threads per take (0 = the cores over
jobs); take_timeout: seconds (0 = no limit); take_memory_mb: address-space limit per take
(0 = none). force: redo every take; retry_failed: redo the failed ones; merge: only
rebuild the summary from the takes' records; shard: 'i/n' runs the takes at positions
p % n == i. executable: the CLI the workers run ('' = $MOCAPSOLVE_CLI, else mocapsolve on
PATH, else the build tree's).
Returns a dict: 'kind' ('ran', 'merged', 'manifest_only', 'empty_shard'), 'done',
'failed' (takes; a failed take is not an exception), 'summary' (summary.json's contents),
'summary_base'. Bad flags or a bad manifest raise ValueError with the CLI's message.
Keywords: the delivery options (formats='glb,fbx,bvh'), every take's when given (over the
manifest's defaults; a take's own value still wins), as the CLI's --formats.
Releases the GIL.)doc");

  m.def("view", [](const std::string& out, const std::string& markers, const std::string& motion,
                   const std::vector<std::string>& characters, const std::string& compare,
                   const std::string& repair_report, const std::string& falloff, const SubjectPtr& subject,
                   const std::string& skeleton, double amc_fps, const std::string& animation, double sample_fps,
                   const std::string& skeleton_units, const std::string& character_animation, const std::string& up,
                   const std::string& title) {
        if (!IsTextOutputPath(out, ".html") || out == "-") throw py::value_error(out + ": expected an .html page");
        for (const std::string* path : {&markers, &motion, &compare, &repair_report, &falloff, &skeleton}) {
          if (!path->empty()) RequireReadable(*path);
        }
        for (const std::string& path : characters) RequireReadable(path);
        ViewInputs inputs;
        inputs.markers = markers;
        inputs.motion = motion;
        inputs.characters = characters;
        inputs.compare = compare;
        inputs.repair_report = repair_report;
        inputs.falloff = falloff;
        inputs.subject = markers.empty() ? nullptr : subject.get();
        inputs.skeleton = skeleton;
        inputs.amc_fps = amc_fps;
        inputs.animation = animation;
        inputs.sample_fps = sample_fps;
        inputs.skeleton_units = skeleton_units;
        ViewConfig config;
        config.character_animation = character_animation;
        config.up = up;
        config.title = title;
        config.page_name = out;
        ViewResult result;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunView(inputs, config, &result);
          if (status.ok()) status = WriteFileAtomically(out, result.html);
        }
        for (const std::string& warning : result.warnings) py::module_::import("warnings").attr("warn")(warning);
        ThrowIfError(status);
        const ViewScene& scene = result.scene;
        py::dict summary;
        summary["frames"] = scene.num_frames();
        summary["marker_sets"] = scene.markers.size();
        summary["skeletons"] = scene.skeletons.size();
        summary["characters"] = scene.characters.size();
        summary["title"] = scene.title;
        summary["notes"] = scene.notes;
        summary["marker_rms_mm"] = result.residual_samples > 0 ? py::object(py::float_(result.marker_rms_mm)) : py::none();
        return summary;
      }, py::arg("out"), py::kw_only(), py::arg("markers") = "", py::arg("motion") = "",
      py::arg("characters") = std::vector<std::string>(), py::arg("compare") = "", py::arg("repair_report") = "",
      py::arg("falloff") = "", py::arg("subject") = SubjectPtr(),
      py::arg("skeleton") = "", py::arg("amc_fps") = DeclaredDefault(FileReadSettingOptions(), "amc_fps"),
      py::arg("animation") = DeclaredDefault(FileReadSettingOptions(), "animation"),
      py::arg("sample_fps") = DeclaredDefault(FileReadSettingOptions(), "sample_fps"),
      py::arg("skeleton_units") = DeclaredDefault(FileReadSettingOptions(), "skeleton_units"),
      py::arg("character_animation") = DeclaredDefault(ViewSettingOptions(), "character_animation"),
      py::arg("up") = DeclaredDefault(ViewSettingOptions(), "up"),
      py::arg("title") = DeclaredDefault(ViewSettingOptions(), "title"),
      R"doc(Writes one self-contained browser page to out (.html), as `mocapsolve view` (the same
task, the same bytes): markers (a .c3d/.trc path), a motion (.bvh, .amc with skeleton= its
.asf, .glb/.gltf/.fbx with animation= and sample_fps=; amc_fps: an .amc's frame rate;
skeleton_units: the unit of a skeleton that states none), characters (.glb/.gltf paths,
each playing character_animation, default its last), compare (a second take ghosted: a
marker file with markers, or a motion with motion), repair_report (a repair --report
.json: repaired samples coloured by reason), falloff (a propagate --weights_csv .csv on
the timeline). With subject (read_subject or subject()) the markers are mapped onto its
skeleton and the motion's marker residual is drawn; otherwise each file is shown in its
own unit with its up axis from up ('auto', 'x', 'y' or 'z'). title: the page's title
(default: the files' names). The viewer's runtime must be installed
(scripts/viewer_tools.sh; $MOCAPSOLVE_VIEWER_TOOLS).
Returns a dict: 'frames', 'marker_sets', 'skeletons', 'characters', 'title', 'notes' and
'marker_rms_mm' (with a subject and a motion; else None). Releases the GIL.)doc");
}

}  // namespace mocapsolve::python
