#include "apps/pipeline_flags.h"

#include <cstdio>

#include "apps/common_flags.h"
#include "apps/delivery_flags.h"
#include "apps/option_flags.h"
#include "apps/progress.h"
#include "apps/pyramid_flags.h"
#include "apps/repair_flags.h"
#include "apps/retarget_flags.h"
#include "apps/view_flags.h"
#include "io/comma_list.h"
#include "pipeline/quality_gate.h"
#include "pipeline/take_windows.h"
#include "settings/delivery_settings.h"
#include "settings/foot_joint_settings.h"
#include "settings/skeleton_fit_settings.h"
#include "settings/label_settings.h"
#include "settings/memory_settings.h"
#include "settings/retarget_run_settings.h"
#include "settings/take_settings.h"
#include "settings/pyramid_settings.h"
#include "settings/repair_settings.h"
#include "settings/retarget_settings.h"
#include "settings/view_page_settings.h"

namespace mocapsolve {

const std::string& PipelineOptionFlags() {
  static const std::string* const names = new std::string(
      TakeSettingOptions().Names() + "," + PyramidSettingOptions().Names() + "," + QualityGateOptions().Names() + "," +
      RetargetRunSettingOptions().Only("animation_only").Names() + "," + DeliverySettingOptions().Names() + "," +
      RepairSettingOptions().Names() + "," + RepairSolverOptions().Names() + "," + RetargetSettingOptions().Names() +
      "," + FootJointOption().Names() + "," + LabelSettingOptions().Names() + "," + AutoSubjectFitOptions().Names() +
      "," + MemoryOption().Names());
  return *names;
}

Status TakePipelineOptionsFromFlags(const Skeleton& skeleton, TakePipelineOptions* options) {
  Status status = RepairOptionsFromFlags(skeleton, &options->repair);
  if (status.ok()) status = RetargetOptionsFromFlags(&options->retarget);
  TakeSettings take;
  ReadOptionFlags(TakeSettingOptions(), &take);
  options->filter_levels = take.filter_levels;
  options->label = take.label;
  options->window_frames = take.window_frames;
  options->window_context_frames = take.window_context_frames;
  options->window_seam_blend_frames = take.window_seam_blend_frames;
  ReadOptionFlags(LabelSettingOptions(), &options->labelling);
  ReadOptionFlags(RepairSolverOptions(), &options->label_solver);
  options->num_threads = options->label_solver.num_threads;  // The same --num_threads as repair's.
  if (status.ok()) status = PyramidOptionsFromFlags(take.filter_levels, &options->filter);
  if (!status.ok()) return status;
  ReadOptionFlags(QualityGateOptions(), &options->gate);
  MemorySettings memory;
  ReadOptionFlags(MemoryOption(), &memory);
  options->memory_mb = memory.memory_mb;
  status = ClipDeliveryFromFlags(&options->delivery);
  if (!status.ok()) return status;
  std::string error;
  if (!options->IsValid(&error)) return Status::Error(error);
  return Status::Ok();
}

// The take's page, as --view says (TakeViewPath; a PAGE.html must be no input). *path: ""
// for none.
Status ViewPageOfTake(std::string* path) {
  ViewPageSetting view;
  ReadOptionFlags(TakeViewPageOption(), &view);
  if (view.view != "auto" && view.view != "off") {
    std::vector<std::string> inputs = {Files().subject, Files().markers};
    for (const std::string& character : SplitCommaList(Files().character)) inputs.push_back(character);
    Status status = CheckViewFlag(inputs);
    if (!status.ok()) return status;
  }
  std::string warning;
  Status status = TakeViewPath(view.view, Files().out_dir, path, &warning);
  // A warning, not progress: printed with --quiet too.
  if (!warning.empty()) std::fprintf(stderr, "warning: pipeline: %s\n", warning.c_str());
  return status;
}

Status RunPipelineTake(const TakeInputs& inputs, const TakePipelineOptions& options,
                       const CharacterFileOptions& files, std::string* view_path, TakeResult* result) {
  Status status = Status::Ok();
  const bool windowed = TakeRunsInWindows(inputs, options, &status);
  if (!status.ok()) return status;
  const bool dropped_page = windowed && !view_path->empty();
  if (dropped_page) {
    ViewPageSetting view;
    ReadOptionFlags(TakeViewPageOption(), &view);
    if (view.view != "auto") return Status::Error("--view=" + view.view + ": no page for a take over --window_frames");
    view_path->clear();
  }
  std::unique_ptr<Progress> progress;
  std::string shown;
  const PipelineProgress show = [&](const std::string& stage, int done, int total) {
    if (stage != shown) {
      SetStage(stage);
      progress = std::make_unique<Progress>("pipeline: " + stage, total, Console().quiet);
      shown = stage;
    }
    progress->Update(done);
  };
  if (!windowed) return RunTakePipeline(inputs, options, result, show);
  status = RunTakeInWindows(Files().out_dir, inputs, options, files, result, show);
  // Only once the take ran: a take refused says so in one line.
  if (status.ok() && dropped_page) {
    std::fprintf(stderr, "warning: pipeline: no view.html (--view=auto): the take runs in windows (--window_frames)\n");
  }
  return status;
}

Status PipelineSubjectFromFlags(Subject* subject, std::unique_ptr<AutoSubjectResult>* fitted) {
  SetStage("inputs");
  if (!Files().subject.empty() && Files().subject != kAutoSubject) return ReadSubject(Files().subject, subject);
  SetStage("subject");
  SkeletonFitSettings settings;
  ReadOptionFlags(AutoSubjectFitOptions(), &settings);
  SolverSettings solver;
  ReadOptionFlags(RepairSolverOptions(), &solver);
  if (!Console().quiet) {
    std::fprintf(stderr, "pipeline: %s: fitting the subject to the take (--subject=auto)\n", Files().markers.c_str());
  }
  auto fit = std::make_unique<AutoSubjectResult>();
  Status status = FitAutoSubject(Files().markers, settings, solver, fit.get(), [&](const SkeletonFitEvent& e) {
    bool to_stdout = false;
    const std::string line = SkeletonFitEventLine(e, fit->inputs.templ.skeleton, &to_stdout);
    if (!Console().quiet && !line.empty()) std::fprintf(stderr, "  %s", line.c_str());
  });
  if (!status.ok()) return status;
  std::fputs(AutoSubjectLine(*fit).c_str(), stdout);
  *subject = fit->fit.subject;
  *fitted = std::move(fit);
  return Status::Ok();
}

void AddPipelineSubject(const AutoSubjectResult* fitted, JsonObject* report) {
  if (fitted == nullptr) {
    report->Add("subject", Files().subject);
  } else {
    report->Add("subject", "subject.json").Add("subject_fit", AutoSubjectReport(*fitted));
  }
}

}  // namespace mocapsolve
