// The pipeline's flags (apps/pipeline_command.cc): the names a --config file may set, and
// the TakePipelineOptions made from the parsed flags (repair, retarget, filter, gate,
// delivery, --memory_mb: settings/memory_settings.h, included here for the command's option
// list), each through its settings' one conversion.
#ifndef MOCAPSOLVE_APPS_PIPELINE_FLAGS_H_
#define MOCAPSOLVE_APPS_PIPELINE_FLAGS_H_

#include <memory>
#include <string>

#include <gflags/gflags.h>

#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "pipeline/take_pipeline.h"
#include "settings/memory_settings.h"
#include "tasks/auto_subject_task.h"

namespace mocapsolve {

// The options a config file may set and --print_config prints, comma-separated.
const std::string& PipelineOptionFlags();

// The take's page, as --view says (auto, off or PAGE.html, which must be no input; a
// missing viewer runtime is a warning for auto, an error for a page asked for): "" for none.
Status ViewPageOfTake(std::string* path);

// Runs the take with a progress display: RunTakePipeline, or, over --window_frames frames,
// RunTakeInWindows (pipeline/take_windows.h), which writes its files but report.json into
// --out_dir already; such a take has no page: *view_path is cleared with a warning for
// --view=auto, an error for a page asked for.
Status RunPipelineTake(const TakeInputs& inputs, const TakePipelineOptions& options,
                       const CharacterFileOptions& files, std::string* view_path, TakeResult* result);

// The take's subject: --subject's file, or with --subject=auto (or no --subject) the one
// fitted from the take (tasks/auto_subject_task.h; *fitted holds the fit, else it stays
// null), its rounds shown on stderr unless --quiet.
Status PipelineSubjectFromFlags(Subject* subject, std::unique_ptr<AutoSubjectResult>* fitted);

// The report's "subject" (--subject's file, or "subject.json" when fitted) and, when fitted,
// "subject_fit" (AutoSubjectReport: template, method, frames, RMS, checks).
void AddPipelineSubject(const AutoSubjectResult* fitted, JsonObject* report);

// Every stage's options from the flags; errors name the flag.
Status TakePipelineOptionsFromFlags(const Skeleton& skeleton, TakePipelineOptions* options);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_APPS_PIPELINE_FLAGS_H_
