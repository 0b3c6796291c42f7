// mocapsolve view: one self-contained HTML page (viewer/view_page.h) that shows markers,
// a motion, characters, a repair and a falloff in a browser, offline. tasks/view_task.h
// reads the files, pairs them (worlds: with a subject or each file in its own) and builds
// the page; this reads the flags and the subject, and writes the page.
#include <cstdio>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/config_flags.h"
#include "apps/option_flags.h"
#include "io/atomic_file.h"
#include "kinematics/quote_token.h"
#include "tasks/view_task.h"

namespace mocapsolve {
namespace {

Status ViewMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (Files().out.empty()) return Status::Error("--out=PAGE.html is required");
  if (!IsTextOutputPath(Files().out, ".html")) return Status::Error("--out=" + Files().out + ": expected an .html page");
  // A subject (--subject, or --skeleton and --markerset) maps the markers onto its skeleton.
  Subject subject;
  const bool with_subject = !Files().markers.empty() && (!Files().subject.empty() || !Files().markerset.empty());
  if (with_subject) {
    Status status = LoadSubjectFromFlags(&subject);
    if (!status.ok()) return status;
  }
  ViewInputs inputs;
  inputs.markers = Files().markers;
  inputs.motion = Files().motion;
  inputs.characters = SplitCommaList(Files().character);
  inputs.compare = Files().compare;
  inputs.repair_report = Files().repair_report;
  inputs.falloff = Files().falloff;
  inputs.subject = with_subject ? &subject : nullptr;
  inputs.skeleton = Files().skeleton;
  inputs.amc_fps = FileReading().amc_fps;
  inputs.animation = FileReading().animation;
  inputs.sample_fps = FileReading().sample_fps;
  inputs.skeleton_units = FileReading().skeleton_units;
  ViewConfig config;
  ReadOptionFlags<ViewSettings>(ViewSettingOptions(), &config);
  config.page_name = Files().out;
  ViewResult result;
  Status status = RunView(inputs, config, &result);
  for (const std::string& warning : result.warnings) {
    std::fprintf(stderr, "warning: %s\n", TerminalText(warning).c_str());
  }
  if (status.ok()) status = WriteFileAtomically(Files().out, result.html);
  if (!status.ok()) return status;
  if (!Console().quiet) {
    const ViewScene& scene = result.scene;
    char residual[96] = "";
    if (result.residual_samples > 0) {
      std::snprintf(residual, sizeof(residual), ", marker residual RMS %.4g mm", result.marker_rms_mm);
    }
    std::printf("view: %d frames, %zu marker sets, %zu skeletons, %zu characters%s; wrote %s\n", scene.num_frames(),
                scene.markers.size(), scene.skeletons.size(), scene.characters.size(), residual, Files().out.c_str());
  }
  return Status::Ok();
}

}  // namespace

extern const Command kViewCommand = {
    "view", "write a self-contained browser page showing markers, motions, characters, repairs",
    "mocapsolve view [--markers=M.c3d|.trc] [--motion=X.bvh|.amc --skeleton=...] "
    "[--character=C.glb|.gltf[,C2.glb]] [--repair_report=r.json] [--falloff=w.csv] "
    "[--compare=OTHER.c3d|.bvh] --out=PAGE.html\n\n"
    "One HTML file that opens from disk, offline: three.js (installed by scripts/viewer_tools.sh)\n"
    "and the data (base64 binary arrays) inlined. One 3D view (orbit: drag; zoom: wheel),\n"
    "markers coloured by state (observed, missing, repaired by reason), hover or click names\n"
    "a marker; skeletons as bones, --compare ghosted; characters playing beside the source; a\n"
    "timeline with play/pause/step/scrub, the marker residual, repaired intervals and falloffs.\n"
    "With --subject (or --skeleton and --markerset) the markers are mapped onto the skeleton and\n"
    "the residual of --motion is drawn; otherwise each file is shown in its own unit, with its up\n"
    "axis from --up.",
    __FILE__, ViewMain, {SharedOptions("subject,skeleton,skeleton_units,markerset,axes,marker_scale,markers,motion,character,out,amc_fps,animation,sample_fps,repair_report,falloff,compare"),
     ViewSettingOptions().options()}};

}  // namespace mocapsolve
