// mocapsolve pipeline: one take from markers to animated characters
// (pipeline/take_pipeline.h): repair and solve, optional filtering, retargeting onto each
// character, the quality gate; outputs in --out_dir.
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "settings/foot_joint_settings.h"
#include "settings/label_settings.h"
#include "settings/retarget_run_settings.h"
#include "settings/take_settings.h"
#include "apps/common_flags.h"
#include "apps/config_flags.h"
#include "apps/option_flags.h"
#include "apps/pipeline_flags.h"
#include "apps/progress.h"
#include "io/comma_list.h"
#include "io/marker_file.h"
#include "io/motion_file.h"
#include "pipeline/quality_gate.h"
#include "pipeline/take_pipeline.h"
#include "settings/delivery_settings.h"
#include "settings/pyramid_settings.h"
#include "settings/repair_settings.h"
#include "settings/retarget_settings.h"
#include "settings/skeleton_fit_settings.h"
#include "settings/view_page_settings.h"
#include "tasks/take_summary.h"

namespace mocapsolve {

extern const Command kPipelineCommand;  // Below: its declared options check --config's values.

namespace {

Status RunPipeline(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (!Files().config.empty()) {
    Status status = ApplyConfigFile(Files().config, PipelineOptionFlags());
    if (status.ok()) status = CheckOptionFlags(kPipelineCommand.options);
    if (!status.ok()) return status;
  }
  if (Console().print_config) {
    std::printf("%s\n", ConfigJson(PipelineOptionFlags()).c_str());
    return Status::Ok();
  }
  if (Files().markers.empty() || Files().out_dir.empty()) return Status::Error("--markers and --out_dir are required");
  if (!IsMarkerFile(Files().markers)) return Status::Error(Files().markers + ": expected a .c3d or .trc");
  std::string view_path;
  Status status = ViewPageOfTake(&view_path);
  if (!status.ok()) return status;
  Subject subject;
  std::unique_ptr<AutoSubjectResult> fitted;
  status = PipelineSubjectFromFlags(&subject, &fitted);
  if (!status.ok()) return status;
  TakePipelineOptions options;
  status = TakePipelineOptionsFromFlags(subject.skeleton, &options);
  if (!status.ok()) return status;
  TakeInputs inputs;
  TakeSettings take;
  ReadOptionFlags(TakeSettingOptions(), &take);
  inputs.name = take.take_name.empty() ? FileStem(Files().markers) : take.take_name;
  RetargetRunSettings run;
  ReadOptionFlags(RetargetRunSettingOptions(), &run);
  inputs.subject = &subject;
  inputs.markers_path = Files().markers;
  inputs.character_paths = SplitCommaList(Files().character);
  inputs.subject_from_take = fitted != nullptr;
  DeliverySettings delivery;
  ReadOptionFlags(DeliverySettingOptions(), &delivery);
  CharacterFileOptions character_files;
  status = CharacterFilesFromSettings(delivery, run.animation_only, &character_files);
  if (status.ok()) status = CheckCharacterFiles(Files().out_dir, inputs, character_files);
  if (!status.ok()) return status;
  TakeResult result;
  status = RunPipelineTake(inputs, options, character_files, &view_path, &result);
  if (!status.ok()) return status;
  JsonObject report = TakeReport(inputs, result);
  AddPipelineSubject(fitted.get(), &report);
  report.Add("command", "pipeline").Add("version", Version()).Add("config", Files().config)
      .Add("animation_only", run.animation_only)
      .Add("options", JsonValue::Raw(ConfigJson(PipelineOptionFlags())));
  const bool in_take_folder = view_path == ViewPagePath(Files().out_dir);
  report.Add("view", view_path.empty() ? JsonValue() : JsonValue(in_take_folder ? "view.html" : view_path));
  SetStage("writing");
  status = MakeFolders(Files().out_dir);
  if (status.ok() && fitted) status = WriteSubject(AutoSubjectPath(Files().out_dir), fitted->fit.subject);
  if (status.ok()) status = WriteTakeOutputs(Files().out_dir, inputs, result, report, view_path, character_files);
  if (status.ok()) status = WriteReport(report);
  if (!status.ok()) return status;
  std::fputs(TakeSummary(inputs, result).c_str(), stdout);
  const size_t files = result.characters.size() * character_files.formats.size();
  std::printf("wrote %s (%srepaired markers, solved.bvh, %zu character file%s, report.json%s%s)\n",
              Files().out_dir.c_str(), fitted ? "subject.json, " : "", files, files == 1 ? "" : "s",
              view_path.empty() ? "" : ", ", in_take_folder ? "view.html" : view_path.c_str());
  if (result.verdict.pass) {
    std::printf("quality gate: pass\n");
    return Status::Ok();
  }
  std::fprintf(stderr, "mocapsolve pipeline: %s: quality gate failed: %s\n", inputs.name.c_str(),
               TakeGateFailures(result).c_str());
  SetExitCodeOnSuccess(3);
  return Status::Ok();
}

}  // namespace

extern const Command kPipelineCommand = {
    "pipeline", "one take end to end: markers -> repair and solve -> filter -> characters",
    "mocapsolve pipeline [--subject=S.json|auto] --markers=TAKE.c3d|.trc [--character=C.glb[,C2.glb]] "
    "--out_dir=DIR [--view=auto|off|PAGE.html] [--config=pipeline.json] [--report=r.json]\n"
    "       mocapsolve pipeline --print_config [--config=pipeline.json]\n\n"
    "--subject=auto or none: the subject is first fitted to the take as `fit_skeleton` fits it with\n"
    "no template (shipped CMU subject 2; by labels, else by segments from the data; up axis from the\n"
    "data; fit options: --fit_max_frames=600 ...) and must pass its checks (--check), else exit 1,\n"
    "nothing written. DIR/subject.json keeps it for the actor's next takes; report: \"subject_fit\".\n"
    "Labels the take's points first when the file lacks some of the subject's labels (a raw,\n"
    "unlabelled capture; --label=auto|never|always and the label options, as `mocapsolve label`),\n"
    "then runs it through repair (thesis ch. 3: robust reference, gap detection and Hermite\n"
    "refill, re-solve), optional multiresolution filtering (--filter_levels), and retargeting\n"
    "onto each character (thesis ch. 4, the character's own mesh bound to the subject's\n"
    "skeleton), then checks the quality gate. Writes DIR/repaired.c3d (or .trc),\n"
    "DIR/solved.bvh, DIR/<character>.glb (the character file plus the take as a new\n"
    "animation; --animation_only: the character's skeleton, skin and the take, no meshes;\n"
    "--formats=glb,fbx,bvh adds DIR/<character>.fbx and .bvh; --frames/--seconds and\n"
    "--out_fps cut and resample the take in every character file)\n"
    "and DIR/report.json (stage timings, marker residuals, repaired intervals,\n"
    "retarget error, foot skating, the gate's verdict), all together or none, and the take's\n"
    "browser page: --view=auto (default) DIR/view.html when the viewer's runtime is installed\n"
    "(scripts/viewer_tools.sh), else a warning and no page; --view=PAGE.html requires it (a\n"
    "missing runtime is an error); --view=off writes none.\n"
    "A take of more than --window_frames frames (18,000: 2.5 min at 120 Hz) runs window by window,\n"
    "each window with --window_context_frames (600) more on each side solved and dropped, in\n"
    "bounded memory, in order (each starts from the last one's solve); its files are written as\n"
    "the windows finish, report.json combines their figures (\"windows\": the seams' differences). Such a take\n"
    "is not labelled first, is delivered whole, as glb only, and has no page.\n"
    "Exit code: 0 done, 1 bad input or a failed stage (nothing written), 3 the take failed\n"
    "the quality gate (outputs written, the report says why).",
    __FILE__, RunPipeline,
    {SharedOptions("subject,markers,character,out_dir,config,print_config,report"),
     TakeSettingOptions().options(), RetargetRunSettingOptions().Only("animation_only").options(),
     FootJointOption().options(), RepairSolverOptions().options(),
     RepairSettingOptions().options(), RetargetSettingOptions().options(), QualityGateOptions().options(),
     PyramidSettingOptions().options(), DeliverySettingOptions().options(), TakeViewPageOption().options(),
     LabelSettingOptions().options(), AutoSubjectFitOptions().options(), MemoryOption().options()}};

}  // namespace mocapsolve
