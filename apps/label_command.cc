// mocapsolve label: a take of unlabelled points (any labels, any order, ghosts, dropouts)
// labelled with a subject's markers (problems/marker_label/marker_labeller.h).
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "apps/progress.h"
#include "io/atomic_file.h"
#include "io/marker_file.h"
#include "pipeline/subject.h"
#include "settings/repair_settings.h"
#include "tasks/label_task.h"

namespace mocapsolve {
namespace {

Status LabelMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (Files().markers.empty()) return Status::Error("--markers is required");
  if (Files().subject.empty() && (Files().skeleton.empty() || Files().markerset.empty())) {
    return Status::Error("--subject (or --skeleton and --markerset) is required");
  }
  if (Files().out.empty()) return Status::Error("--out is required");
  if (!IsMarkerFile(Files().out)) return Status::Error(Files().out + ": expected .c3d or .trc");
  Status status = CheckOutputsApart({Files().out, Files().report},
                                    {Files().markers, Files().subject, Files().skeleton, Files().markerset});
  if (!status.ok()) return status;
  LabelConfig config;
  ReadOptionFlags(LabelSettingOptions(), &config.label);
  ReadOptionFlags(RepairSolverOptions(), &config.solver);

  SetStage("inputs");
  Subject subject;
  status = LoadSubjectFromFlags(&subject);
  if (!status.ok()) return status;
  MarkerTrajectories file;
  status = ReadMarkerFile(Files().markers, &file);
  if (!status.ok()) return status;

  SetStage("label");
  std::unique_ptr<Progress> progress;
  const LabelProgress show_progress = [&](int done, int total) {
    if (!progress) progress = std::make_unique<Progress>("label", total, Console().quiet);
    progress->Update(done);
  };
  LabelResult result;
  status = RunLabel(subject, file, Files().markers, config, show_progress, &result);
  if (!status.ok()) return status;

  SetStage("writing");
  status = WriteMarkerFile(Files().out, result.markers);
  if (!status.ok()) return status;
  if (!Console().quiet) std::printf("%s\nwrote %s\n", result.summary.c_str(), Files().out.c_str());
  JsonObject json;
  json.Add("markers", Files().markers).Add("out", Files().out).Merge(result.report);
  return WriteReport(json);
}

}  // namespace

extern const Command kLabelCommand = {
    "label", "labels a take of unlabelled marker points with a subject's markers",
    "mocapsolve label (--subject=S.json | --skeleton=S --markerset=J.json) --markers=RAW.c3d|.trc "
    "--out=LABELLED.c3d|.trc [--report=r.json]\n\n"
    "Every point of the take is a candidate, whatever its label: the points may be in any order,\n"
    "with ghosts and dropouts. The body is found in the first frames without assuming a pose\n"
    "(the triangles of each joint's markers matched in the cloud, each placement refined by\n"
    "matching and solving), then tracked frame by frame: each marker predicted at constant\n"
    "velocity (--gate) or, after a gap, from the pose solved at the previous frame\n"
    "(--reacquire_gate), points matched one to one with a cost for an empty label, and a match\n"
    "less confident than --min_confidence left unlabelled. A lost body is looked for again.\n"
    "--out holds the subject's markers, then the points left unlabelled as '*1', '*2', ...\n"
    "A take whose points match no placement of the subject is an error giving the best match.",
    __FILE__, LabelMain,
    {SharedOptions("subject,skeleton,skeleton_units,markers,markerset,axes,marker_scale,out,report"),
     LabelSettingOptions().options(), RepairSolverOptions().options()}};

}  // namespace mocapsolve
