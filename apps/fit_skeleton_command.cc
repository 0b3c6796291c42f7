// mocapsolve fit_skeleton: a subject (bone lengths, marker attachments and offsets) from
// its markers alone, starting from a template subject. The rounds, the checks and the
// report are the library's (tasks/fit_skeleton_task.h, which the Python module's
// fit_skeleton() calls too); this file reads the flags, prints and writes.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "apps/progress.h"
#include "apps/solver_flags.h"
#include "io/bvh_writer.h"
#include "io/marker_set_file.h"
#include "pipeline/subject.h"
#include "tasks/fit_skeleton_task.h"


namespace mocapsolve {
namespace {

Status RunFitSkeleton(const std::vector<std::string>& arguments) {
  const auto start = std::chrono::steady_clock::now();
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  Status status = CheckSkeletonFitInputsGiven(!Files().template_subject.empty(), !Files().skeleton.empty(),
                                              !Files().markerset.empty(), !FileReading().skeleton_units.empty(),
                                              !Files().markers.empty());
  if (!status.ok()) return status;
  if (Files().out.empty() && Files().out_subject.empty()) return Status::Error("--out or --out_subject is required");
  if (!Files().out.empty() && !IsTextOutputPath(Files().out, ".bvh")) return Status::Error(Files().out + ": expected a .bvh");
  for (const std::string& json : {Files().out_markerset, Files().out_subject}) {
    if (!json.empty() && !IsTextOutputPath(json, ".json")) return Status::Error(json + ": expected a .json");
  }
  const std::vector<std::string> outputs = {Files().out, Files().out_markerset, Files().out_subject};
  status = CheckOutputsApart(outputs, {Files().template_subject, Files().skeleton, Files().markers, Files().markerset});
  if (!status.ok()) return status;
  SkeletonFitSettings settings;
  ReadOptionFlags(SkeletonFitSettingOptions(), &settings);
  status = ValidateSkeletonFitSettings(settings);
  if (!status.ok()) return status;

  SkeletonFitInputs inputs;
  inputs.markers_path = Files().markers;
  inputs.axes = FileReading().axes;
  inputs.marker_scale = FileReading().marker_scale;
  inputs.amc_fps = FileReading().amc_fps;
  status = LoadSkeletonFitTemplate(Files().template_subject, Files().skeleton, Files().markerset, FileReading().skeleton_units,
                                   &inputs);
  if (!status.ok()) return status;
  MarkerSolveOptions solve_options;
  status = MarkerSolveOptionsFromFlags(inputs.templ.skeleton.unit(), &solve_options);
  if (!status.ok()) return status;

  // Progress: a line per round and per iteration, and the frames of each pose solve.
  std::unique_ptr<Progress> frames_progress;
  int progress_round = -1, progress_iteration = -1;
  const SkeletonFitCallback callback = [&](const SkeletonFitEvent& e) {
    if (e.kind == SkeletonFitEvent::kFrames) {
      if (e.round != progress_round || e.iteration != progress_iteration || !frames_progress) {
        progress_round = e.round;
        progress_iteration = e.iteration;
        frames_progress = std::make_unique<Progress>(
            "  pose solve " + std::to_string(e.iteration + 1) + "/" + std::to_string(e.iterations + 1), e.frames,
            Console().quiet);
      }
      frames_progress->Update(e.frames_done);
      if (e.frames_done >= e.frames) frames_progress.reset();
      return;
    }
    bool to_stdout = false;
    const std::string line = SkeletonFitEventLine(e, inputs.templ.skeleton, &to_stdout);
    if (Console().quiet) return;
    std::fputs(line.c_str(), to_stdout ? stdout : stderr);
    if (to_stdout) std::fflush(stdout);
  };
  SkeletonFitResult result;
  SetStage("fit");
  status = FitSubjectToTake(inputs, settings, solve_options, &result, callback);
  if (!status.ok()) return status;
  const Skeleton& fitted = result.subject.skeleton;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fputs(SkeletonFitSummary(result).c_str(), stdout);
  const JsonObject json = SkeletonFitReportJson(inputs, result);
  if (!result.checks.ok() && settings.check != "off") {
    for (const std::string& failure : result.checks.failures) {
      std::fprintf(stderr, "fit_skeleton: check failed: %s\n", failure.c_str());
    }
    const Status failed = SkeletonFitCheckStatus(inputs, settings, result);
    if (!failed.ok()) {
      Status written = WriteReport(json);
      if (!written.ok()) return written;
      return failed;
    }
  }
  if (!Files().out.empty()) {
    SetStage("writing");
    status = WriteBvh(Files().out, fitted, result.motion, BvhWriteOptions());
    if (!status.ok()) return status;
  }
  if (!Files().out_markerset.empty()) {
    status = WriteMarkerSet(Files().out_markerset, fitted, result.subject.markers);
    if (!status.ok()) return status;
  }
  if (!Files().out_subject.empty()) {
    status = WriteSubject(Files().out_subject, result.subject);
    if (!status.ok()) return status;
  }
  for (const std::string& out : outputs) {
    if (!out.empty()) std::printf("wrote %s\n", out.c_str());
  }
  return WriteReport(json);
}

}  // namespace

extern const Command kFitSkeletonCommand = {
    "fit_skeleton", "fit a subject (bone lengths, marker attachments and offsets) to a take's markers",
    "mocapsolve fit_skeleton --template_subject=T.json --markers=IN.c3d|.trc --out_subject=S.json\n"
    "          [--out=FITTED.bvh] [--out_markerset=S.json] [--axes=x,y,z] [--attach_rounds=12]\n"
    "          [--check=fail|warn|off] [--template_labels=auto|none|T:TAKE,...|FILE] [--report=r.json]\n"
    "   or: --skeleton=T.bvh|.asf --markerset=J.json, or neither: the shipped template (CMU subject 2)\n\n"
    "For captures without a skeleton. Starts from a template subject (skeleton + marker set;\n"
    "--axes/--marker_scale describe the take's file) and fits on the markers the take shares\n"
    "with it by label (--template_labels renames template markers to the take's labels\n"
    "where the take's protocol names the same landmark otherwise; by default a shipped map\n"
    "when the take's labels are its protocol's; when neither gives 3 labels, --associate finds each marker's\n"
    "segment, the up axis and units from the data): per-frame pose solves (the first frame's root from the markers' own\n"
    "geometry) alternate with a Gauss-Newton fit of bone-length scales and marker offsets.\n"
    "Then --attach_rounds times: every marker of the take is attached to the joint it moves\n"
    "least with (among joints whose bone it is within --max_skin_cm of) and the fit runs\n"
    "again with all of them. Constraints: bone scales within [--min_bone_scale,\n"
    "--max_bone_scale] of the template, left = right, offsets within --max_skin_cm of their\n"
    "bone. Then the checks, which do not trust the residual: every marker within 15 cm of\n"
    "its bone, the solved pelvis-to-head direction within 15 degrees (mean) of the markers'\n"
    "own, left/right bone lengths within 5 %, and the marker RMS within 25 mm;\n"
    "--check=fail (default) exits 1 when one fails.\n"
    "Writes the subject (skeleton inline), and optionally the solved motion and marker set.",
    __FILE__, RunFitSkeleton,
    {SharedOptions("template_subject,skeleton,skeleton_units,amc_fps,markers,markerset,axes,marker_scale,out,out_subject,out_markerset,report"),
     SkeletonFitSettingOptions().options(), SolverOptions().Without("mode").options()}};

}  // namespace mocapsolve
