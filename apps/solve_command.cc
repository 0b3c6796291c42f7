// mocapsolve solve: joint angles from optical markers.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/progress.h"
#include "apps/solver_flags.h"
#include "apps/view_flags.h"
#include "io/atomic_file.h"
#include "io/bvh_writer.h"
#include "io/svg_plot.h"
#include "kinematics/forward_kinematics.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "problems/marker_solve/marker_observations.h"
#include "pipeline/take_view.h"
#include "problems/marker_solve/sequence_solver.h"

DEFINE_int32(max_frames, 0, "Solve only the first N frames (0 = all).");
DEFINE_string(plot, "", "Write an SVG plot of the per-frame RMS marker residual to this file.");
DEFINE_string(residuals_csv, "", "Write the written motion's per-frame marker residual as CSV: frame, time (s), "
              "markers observed, RMS and max residual (mm, or skeleton units when the unit is unknown).");

namespace mocapsolve {
namespace {

Status RunSolve(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  std::vector<std::string> inputs;
  Status checked = MarkerTakeInputs(&inputs);
  if (!checked.ok()) return checked;
  if (FLAGS_out.empty()) return Status::Error("--out is required");
  if (!IsTextOutputPath(FLAGS_out, ".bvh")) return Status::Error(FLAGS_out + ": expected a .bvh output");
  for (const std::string& input : inputs) {
    Status status = CheckNotAnInput(FLAGS_out, input);
    if (!status.ok()) return status;
  }
  checked = CheckViewFlag(inputs);
  if (!checked.ok()) return checked;
  const SolverSettings solver = SolverSettingsFromFlags();
  MarkerTake take;
  SetStage("inputs");
  Status status = LoadMarkerTake(&take);
  if (!status.ok()) return status;
  const Skeleton& skeleton = take.skeleton;
  const MarkerSet& markers = take.markers;
  const MarkerTrajectories& trajectories = take.trajectories;
  const MarkerFileToModel& transform = take.transform;
  std::vector<std::vector<Eigen::Vector3d>>& observed = take.observed;
  MarkerSolveOptions frame_options;
  status = MarkerSolveOptionsFromFlags(skeleton.unit(), &frame_options);
  if (!status.ok()) return status;
  frame_options.rest_rotations = take.mean_pose;
  ClipSolveOptions clip_options;
  if (solver.mode == "clip") {
    status = ClipSolveOptionsFromFlags(&clip_options);
    if (!status.ok()) return status;
  }
  if (FLAGS_max_frames > 0 && static_cast<int>(observed.size()) > FLAGS_max_frames) {
    observed.resize(FLAGS_max_frames);
  }

  Motion motion;
  motion.frame_rate = trajectories.frame_rate;
  SequenceSolveReport sequence;
  Progress progress("solve (" + solver.solver + ")", static_cast<int>(observed.size()), FLAGS_quiet);
  SetStage("solve");
  status = SolveSequence(skeleton, markers, observed, frame_options, RestPose(skeleton), &motion,
                         &sequence, [&](int done) { progress.Update(done); });
  if (!status.ok()) return Status::Error(FLAGS_markers + ": " + status.message());
  const double mm_per_unit = skeleton.unit().known() ? skeleton.unit().metres_per_unit * 1000.0 : 0.0;
  const char* unit = mm_per_unit > 0.0 ? "mm" : "skeleton units";
  const double to_output = mm_per_unit > 0.0 ? mm_per_unit : 1.0;
  std::printf("per-frame (%s): %d frames in %.3f s (%.0f frames/s), %ld iterations, RMS marker "
              "residual %.4g %s (worst frame %.4g), unsolved frames %d, at iteration limit %d\n",
              solver.solver.c_str(), sequence.frames, sequence.solve_seconds,
              sequence.solve_seconds > 0 ? sequence.frames / sequence.solve_seconds : 0.0,
              sequence.total_iterations, sequence.rms_marker_error * to_output, unit,
              sequence.max_frame_rms * to_output, sequence.unsolved_frames,
              sequence.unconverged_frames);
  JsonObject report;
  if (FLAGS_subject.empty()) {
    report.Add("skeleton", FLAGS_skeleton).Add("markerset", FLAGS_markerset);
  } else {
    report.Add("subject", FLAGS_subject);
  }
  report.Add("markers", FLAGS_markers).Add("out", FLAGS_out).Add("solver", solver.solver)
      .Add("mode", solver.mode).Add("frames", sequence.frames)
      .Add("marker_to_skeleton_scale", transform.scale).Add("residual_unit", unit);
  JsonObject frame_json;
  frame_json.Add("seconds", sequence.solve_seconds)
      .Add("frames_per_second", sequence.solve_seconds > 0 ? sequence.frames / sequence.solve_seconds : 0.0)
      .Add("iterations", static_cast<double>(sequence.total_iterations))
      .Add("rms_marker_residual", sequence.rms_marker_error * to_output)
      .Add("max_frame_rms", sequence.max_frame_rms * to_output)
      .Add("unsolved_frames", sequence.unsolved_frames)
      .Add("frames_at_iteration_limit", sequence.unconverged_frames)
      .Add("total_final_cost", sequence.total_final_cost);
  report.Add("per_frame", frame_json);

  if (solver.mode == "clip") {
    ClipSolveReport clip;
    if (!FLAGS_quiet) std::fprintf(stderr, "clip solve: %zu frames as one problem...\n", observed.size());
    SetStage("clip solve");
    status = SolveClip(skeleton, markers, observed, clip_options, &motion, &clip);
    if (!status.ok()) return Status::Error(FLAGS_markers + ": " + status.message());
    std::printf("clip (%s): %d parameters, %d residual blocks, %d iterations in %.3f s, cost "
                "%.6g -> %.6g, RMS marker residual %.4g %s\n",
                clip.solver.c_str(), clip.parameters, clip.residual_blocks, clip.iterations, clip.solve_seconds,
                clip.initial_cost, clip.final_cost, clip.rms_marker_error * to_output, unit);
    JsonObject clip_json;
    clip_json.Add("solver", clip.solver).Add("seconds", clip.solve_seconds).Add("iterations", clip.iterations)
        .Add("parameters", clip.parameters).Add("residual_blocks", clip.residual_blocks)
        .Add("initial_cost", clip.initial_cost).Add("final_cost", clip.final_cost)
        .Add("rms_marker_residual", clip.rms_marker_error * to_output);
    report.Add("clip", clip_json);
  }
  if (!FLAGS_residuals_csv.empty()) {
    // Of the motion written (after the clip solve with --mode=clip), frame by frame.
    std::string csv = std::string("frame,time_s,markers_observed,rms_") + (mm_per_unit > 0.0 ? "mm" : "units") +
                      ",max_" + (mm_per_unit > 0.0 ? "mm" : "units") + "\n";
    FkData fk(skeleton);
    const double rate = motion.frame_rate > 0 ? motion.frame_rate : 0.0;
    for (size_t f = 0; f < observed.size(); ++f) {
      ForwardKinematics(skeleton, motion.frames[f], &fk);
      int count = 0;
      double sum = 0.0, worst = 0.0;
      for (int m = 0; m < markers.num_markers(); ++m) {
        if (!observed[f][m].allFinite()) continue;
        const double e = (markers.Position(m, fk) - observed[f][m]).norm() * to_output;
        sum += e * e;
        worst = std::max(worst, e);
        ++count;
      }
      char line[160];
      std::snprintf(line, sizeof(line), "%zu,%.6g,%d,%.6g,%.6g\n", f, rate > 0 ? f / rate : 0.0, count,
                    count > 0 ? std::sqrt(sum / count) : 0.0, worst);
      csv += line;
    }
    SetStage("writing");
    status = WriteFileAtomically(FLAGS_residuals_csv, csv);
    if (!status.ok()) return status;
    report.Add("residuals_csv", FLAGS_residuals_csv);
  }
  status = WriteBvh(FLAGS_out, skeleton, motion, BvhWriteOptions());
  if (!status.ok()) return status;
  std::printf("wrote %s\n", FLAGS_out.c_str());
  if (!FLAGS_plot.empty()) {
    PlotSeries rms{"per-frame " + solver.solver, {}};
    for (double v : sequence.frame_rms) rms.y.push_back(v * to_output);
    status = WriteFileAtomically(FLAGS_plot, LinePlotSvg("RMS marker residual per frame: " + FLAGS_markers,
                                                        "frame", std::string("RMS residual (") + unit + ")",
                                                        {rms}));
    if (!status.ok()) return status;
    std::printf("wrote %s\n", FLAGS_plot.c_str());
  }
  status = WriteViewFlag([&](ViewScene* scene) {
    TakeViewInputs view;
    view.title = "solve: " + FileStem(FLAGS_markers);
    view.skeleton = &skeleton;
    view.markers = &markers;
    view.observed = &observed;
    view.motion = &motion;
    view.frame_rate = motion.frame_rate > 0 ? motion.frame_rate : 30.0;
    return MakeTakeViewScene(view, scene);
  });
  if (!status.ok()) return status;
  return WriteReport(report);
}

const std::string kSolveFlags =
    std::string("subject,skeleton,skeleton_units,markers,markerset,out,axes,marker_scale,report,quiet,plot,residuals_csv,"
                "max_frames,view");

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
    __FILE__, RunSolve, kSolveFlags.c_str(), {SolverOptions().options()}};

}  // namespace mocapsolve
