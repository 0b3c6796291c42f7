// mocapsolve solve: joint angles from optical markers.
#include <algorithm>
#include <cstdio>

#include "apps/command.h"
#include "settings/frame_limit_settings.h"
#include "settings/solver_agreement_settings.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "apps/progress.h"
#include "apps/solver_flags.h"
#include "apps/view_flags.h"
#include "settings/plot_settings.h"
#include "settings/view_page_settings.h"
#include "io/atomic_file.h"
#include "io/bvh_writer.h"
#include "io/motion_file.h"
#include "io/svg_plot.h"
#include "pipeline/take_view.h"
#include "tasks/solve_task.h"

namespace mocapsolve {
namespace {

Status SolveMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  PlotSetting plot_setting;
  ReadOptionFlags(SolvePlotOption(), &plot_setting);
  const std::string& plot = plot_setting.plot;
  std::vector<std::string> inputs;
  Status checked = MarkerTakeInputs(&inputs);
  if (!checked.ok()) return checked;
  if (Files().out.empty()) return Status::Error("--out is required");
  if (!IsTextOutputPath(Files().out, ".bvh")) return Status::Error(Files().out + ": expected a .bvh output");
  for (const std::string& input : inputs) {
    Status status = CheckNotAnInput(Files().out, input);
    if (!status.ok()) return status;
  }
  checked = CheckViewFlag(inputs);
  if (!checked.ok()) return checked;
  SolveConfig config;
  config.solver = SolverSettingsFromFlags();
  FrameLimitSettings limit;
  ReadOptionFlags(FrameLimitOption(), &limit);
  config.max_frames = limit.max_frames;
  ReadOptionFlags(SolverAgreementOptions(), &config.agreement);
  ReadOptionFlags(MemoryOption(), &config.memory);
  const SolverSettings& solver = config.solver;
  MarkerTake take;
  SetStage("inputs");
  Status status = LoadMarkerTake(&take);
  if (!status.ok()) return status;
  const Skeleton& skeleton = take.skeleton;
  const bool known = skeleton.unit().known();
  const char* unit = known ? "mm" : "skeleton units";
  const double to_output = known ? skeleton.unit().metres_per_unit * 1000.0 : 1.0;  // For the plot.
  const int frames = limit.max_frames > 0 ? std::min<int>(limit.max_frames, take.observed.size())
                                          : static_cast<int>(take.observed.size());
  Progress progress("solve (" + solver.solver + ")", frames, Console().quiet);
  SolveProgress show_progress;
  show_progress.frames = [&](int done) { progress.Update(done); };
  show_progress.per_frame_done = [&](const SequenceSolveReport& sequence) {
    std::fputs(PerFrameSolveText(skeleton, solver.solver, sequence).c_str(), stdout);
    if (solver.mode != "clip") return;
    if (!Console().quiet) std::fprintf(stderr, "clip solve: %d frames as one problem...\n", sequence.frames);
    SetStage("clip solve");
  };
  SetStage("solve");
  SolveResult result;
  status = RunSolve(take, config, show_progress, &result);
  if (!status.ok()) return status;
  const SequenceSolveReport& sequence = result.per_frame;
  std::fputs(SolveSummaryText(skeleton, config, result).c_str(), stdout);
  JsonObject report;
  if (Files().subject.empty()) {
    report.Add("skeleton", Files().skeleton).Add("markerset", Files().markerset);
  } else {
    report.Add("subject", Files().subject);
  }
  report.Add("markers", Files().markers).Add("out", Files().out).Merge(result.report);
  if (!Files().residuals_csv.empty()) {
    SetStage("writing");
    status = WriteFileAtomically(Files().residuals_csv, FrameResidualsCsv(take, result.frames, result.motion));
    if (!status.ok()) return status;
    report.Add("residuals_csv", Files().residuals_csv);
  }
  const Motion& motion = result.motion;
  status = WriteBvh(Files().out, skeleton, motion, BvhWriteOptions());
  if (!status.ok()) return status;
  std::printf("wrote %s\n", Files().out.c_str());
  if (!plot.empty()) {
    PlotSeries rms{"per-frame " + solver.solver, {}};
    for (double v : sequence.frame_rms) rms.y.push_back(v * to_output);
    status = WriteFileAtomically(plot, LinePlotSvg("RMS marker residual per frame: " + Files().markers,
                                                        "frame", std::string("RMS residual (") + unit + ")",
                                                        {rms}));
    if (!status.ok()) return status;
    std::printf("wrote %s\n", plot.c_str());
  }
  take.observed.resize(result.frames);  // The page shows the frames solved.
  status = WriteViewFlag([&](ViewScene* scene) {
    TakeViewInputs view;
    view.title = "solve: " + FileStem(Files().markers);
    view.skeleton = &skeleton;
    view.markers = &take.markers;
    view.observed = &take.observed;
    view.motion = &motion;
    view.frame_rate = motion.frame_rate > 0 ? motion.frame_rate : 30.0;
    return MakeTakeViewScene(view, scene);
  });
  if (!status.ok()) return status;
  return WriteReport(report);
}

}  // namespace

extern const Command kSolveCommand = {
    "solve", "joint angles from markers (C3D/TRC) onto a BVH or ASF skeleton, Ceres or DLS",
    "mocapsolve solve (--skeleton=S.asf|S.bvh --markerset=J.json | --subject=S.json) --markers=M.c3d|M.trc "
    "--out=O.bvh [--solver=ceres|dls] [--mode=frame|clip] [--axes=y,z,x] [--report=r.json] [--residuals_csv=r.csv] "
    "[--plot=r.svg] [--view=PAGE.html]\n\n"
    "Solves the root translation and joint rotations per frame (warm-started from the\n"
    "previous frame; the first frame tries 24 root orientations), and with --mode=clip\n"
    "refines all frames as one sparse problem with smoothness. Missing markers are simply\n"
    "left out. Prints the RMS marker residual, iterations and time; --report writes them,\n"
    "--residuals_csv the residual of every frame of the written motion (--plot draws it).",
    __FILE__, SolveMain,
    {SharedOptions("subject,skeleton,skeleton_units,markers,markerset,out,axes,marker_scale,residuals_csv,report"),
     FrameLimitOption().options(), SolverOptions().options(), SolverAgreementOptions().options(), ViewPageOption().options(), SolvePlotOption().options(), MemoryOption().options()}};

}  // namespace mocapsolve
