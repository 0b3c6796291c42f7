#include "tasks/solve_task.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "kinematics/forward_kinematics.h"
#include "pipeline/memory_estimate.h"
#include "pipeline/repair_report.h"
#include "tasks/console_text.h"

namespace mocapsolve {
namespace {

// Skeleton units -> the reports' residual unit: mm when the skeleton's unit is known.
double ResidualScale(const Skeleton& skeleton) {
  return skeleton.unit().known() ? skeleton.unit().metres_per_unit * 1000.0 : 1.0;
}

const char* ResidualUnit(const Skeleton& skeleton) { return skeleton.unit().known() ? "mm" : "skeleton units"; }

constexpr int kListedFrames = 20;  // Differing frames the report lists, worst first.

// The solver_agreement block: the share of frames within the tolerance, each solver's
// time per frame and RMS, and the frames that differ most (costs as the solvers report
// them; RMS in the report's unit).
JsonObject AgreementJson(const SolverAgreementReport& agreement, double scale) {
  auto per_frame_ms = [](const SequenceSolveReport& r) { return r.frames > 0 ? 1e3 * r.solve_seconds / r.frames : 0.0; };
  std::vector<JsonObject> worst;
  for (const SolverAgreementFrame& f : agreement.worst) {
    JsonObject frame;
    frame.Add("frame", f.frame).Add("dls_cost", f.dls_cost).Add("ceres_cost", f.ceres_cost)
        .Add("relative_difference", f.relative).Add("dls_rms", f.dls_rms * scale).Add("ceres_rms", f.ceres_rms * scale);
    worst.push_back(frame);
  }
  JsonObject json;
  json.Add("tolerance", agreement.tolerance).Add("frames_compared", agreement.frames_compared)
      .Add("frames_within", agreement.frames_within).Add("fraction_within", agreement.fraction_within)
      .Add("dls_ms_per_frame", per_frame_ms(agreement.dls)).Add("ceres_ms_per_frame", per_frame_ms(agreement.ceres))
      .Add("dls_rms_marker_residual", agreement.dls.rms_marker_error * scale)
      .Add("ceres_rms_marker_residual", agreement.ceres.rms_marker_error * scale)
      .Add("worst_frames", worst);
  return json;
}

}  // namespace

std::string HeldJointsText(const Skeleton& skeleton, const SequenceSolveReport& sequence) {
  auto list = [&](const std::vector<int>& frames) {
    std::string text;
    for (size_t j = 0; j < frames.size(); ++j) {
      if (frames[j] == 0) continue;
      text += (text.empty() ? "" : ", ") + skeleton.name(static_cast<int>(j)) + " " + std::to_string(frames[j]);
    }
    return text;
  };
  const std::string whole = list(sequence.held_frames), twist = list(sequence.twist_held_frames);
  if (twist.empty()) return whole;
  return (whole.empty() ? "none" : whole) + "; about the line to their one seen marker only: " + twist;
}

std::string PerFrameSolveText(const Skeleton& skeleton, const std::string& solver,
                              const SequenceSolveReport& sequence) {
  const double scale = ResidualScale(skeleton);
  std::string text;
  AppendF(&text, "per-frame (%s): %d frames in %.3f s (%.0f frames/s), %ld iterations, RMS marker "
          "residual %.4g %s (worst frame %.4g), unsolved frames %d, at iteration limit %d\n",
          solver.c_str(), sequence.frames, sequence.solve_seconds,
          sequence.solve_seconds > 0 ? sequence.frames / sequence.solve_seconds : 0.0, sequence.total_iterations,
          sequence.rms_marker_error * scale, ResidualUnit(skeleton), sequence.max_frame_rms * scale,
          sequence.unsolved_frames, sequence.unconverged_frames);
  const std::string held = HeldJointsText(skeleton, sequence);
  if (!held.empty()) AppendF(&text, "hidden joints held at the subject's mean pose (frames): %s\n", held.c_str());
  return text;
}

std::string SolveSummaryText(const Skeleton& skeleton, const SolveConfig& config, const SolveResult& result) {
  std::string text;
  if (config.agreement.compare_solvers) {
    const SolverAgreementReport& a = result.agreement;
    AppendF(&text, "solver agreement: %d of %d frames (%.2f %%) with dls and ceres final costs within %g; %zu "
            "listed in the report\n", a.frames_within, a.frames_compared, 100.0 * a.fraction_within, a.tolerance,
            a.worst.size());
  }
  if (config.solver.mode == "clip") {
    const ClipSolveReport& clip = result.clip;
    AppendF(&text, "clip (%s): %d parameters, %d residual blocks, %d iterations in %.3f s, cost %.6g -> %.6g, RMS "
            "marker residual %.4g %s\n", clip.solver.c_str(), clip.parameters, clip.residual_blocks,
            clip.iterations, clip.solve_seconds, clip.initial_cost, clip.final_cost,
            clip.rms_marker_error * ResidualScale(skeleton), ResidualUnit(skeleton));
  }
  return text;
}

Status RunSolve(const MarkerTake& take, const SolveConfig& config, const SolveProgress& progress,
                SolveResult* result) {
  *result = SolveResult();
  const SolverSettings& solver = config.solver;
  if (config.max_frames < 0) return Status::Error("--max_frames: expected a value >= 0, got " +
                                                  std::to_string(config.max_frames));
  const Skeleton& skeleton = take.skeleton;
  MarkerSolveOptions frame_options;  // Validates every solver option.
  Status status = MarkerSolveOptionsFromSettings(solver, skeleton, take.mean_pose, &frame_options);
  if (!status.ok()) return status;
  ClipSolveOptions clip_options;
  if (solver.mode == "clip") {
    status = ClipSolveOptionsFromSettings(solver, &clip_options);
    if (!status.ok()) return status;
  }
  const int total = static_cast<int>(take.observed.size());
  result->frames = config.max_frames > 0 ? std::min(config.max_frames, total) : total;
  if (solver.mode == "clip") {  // The whole-clip problem's memory, before the per-frame solve.
    status = CheckMemoryLimit(ClipSolveMemory(result->frames, take.markers.num_markers()), config.memory.memory_mb,
                              take.name);
    if (!status.ok()) return status;
  }
  std::vector<std::vector<Eigen::Vector3d>> cut;
  if (result->frames < total) cut.assign(take.observed.begin(), take.observed.begin() + result->frames);
  const auto& observed = result->frames < total ? cut : take.observed;

  result->motion.frame_rate = take.trajectories.frame_rate;
  SequenceSolveReport& sequence = result->per_frame;
  status = SolveSequence(skeleton, take.markers, observed, frame_options, RestPose(skeleton), &result->motion,
                         &sequence, progress.frames);
  if (!status.ok()) return Status::Error(take.name + ": " + status.message());
  const double scale = ResidualScale(skeleton);
  result->report.Add("solver", solver.solver).Add("mode", solver.mode).Add("frames", sequence.frames)
      .Add("marker_to_skeleton_scale", take.transform.scale).Add("residual_unit", ResidualUnit(skeleton));
  JsonObject frame_json;
  frame_json.Add("seconds", sequence.solve_seconds)
      .Add("frames_per_second", sequence.solve_seconds > 0 ? sequence.frames / sequence.solve_seconds : 0.0)
      .Add("iterations", static_cast<double>(sequence.total_iterations))
      .Add("rms_marker_residual", sequence.rms_marker_error * scale)
      .Add("max_frame_rms", sequence.max_frame_rms * scale)
      .Add("unsolved_frames", sequence.unsolved_frames)
      .Add("frames_at_iteration_limit", sequence.unconverged_frames)
      .Add("total_final_cost", sequence.total_final_cost).Add("residual_unit", ResidualUnit(skeleton));
  if (!sequence.held_frames.empty()) {
    frame_json.Add("hidden_joints_held_frames", HeldJointsJson(skeleton, sequence.held_frames));
  }
  if (!sequence.twist_held_frames.empty()) {
    frame_json.Add("twist_held_frames", HeldJointsJson(skeleton, sequence.twist_held_frames));
  }
  result->report.Add("per_frame", frame_json);
  if (config.agreement.compare_solvers) {
    status = CompareSolvers(skeleton, take.markers, observed, frame_options, RestPose(skeleton),
                            config.agreement.agreement_tolerance, kListedFrames, &result->agreement);
    if (!status.ok()) return Status::Error(take.name + ": " + status.message());
    result->report.Add("solver_agreement", AgreementJson(result->agreement, scale));
  }
  if (progress.per_frame_done) progress.per_frame_done(sequence);
  if (solver.mode != "clip") return Status::Ok();

  ClipSolveReport& clip = result->clip;
  status = SolveClip(skeleton, take.markers, observed, clip_options, &result->motion, &clip);
  if (!status.ok()) return Status::Error(take.name + ": " + status.message());
  JsonObject clip_json;
  clip_json.Add("solver", clip.solver).Add("seconds", clip.solve_seconds).Add("iterations", clip.iterations)
      .Add("parameters", clip.parameters).Add("residual_blocks", clip.residual_blocks)
      .Add("initial_cost", clip.initial_cost).Add("final_cost", clip.final_cost)
      .Add("rms_marker_residual", clip.rms_marker_error * scale).Add("brief", clip.brief);
  result->report.Add("clip", clip_json);
  return Status::Ok();
}

std::string FrameResidualsCsv(const MarkerTake& take, int frames, const Motion& motion) {
  const Skeleton& skeleton = take.skeleton;
  const bool known = skeleton.unit().known();
  const double scale = ResidualScale(skeleton);
  std::string csv = std::string("frame,time_s,markers_observed,rms_") + (known ? "mm" : "units") + ",max_" +
                    (known ? "mm" : "units") + "\n";
  FkData fk(skeleton);
  const double rate = motion.frame_rate > 0 ? motion.frame_rate : 0.0;
  for (int f = 0; f < frames; ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    int count = 0;
    double sum = 0.0, worst = 0.0;
    for (int m = 0; m < take.markers.num_markers(); ++m) {
      if (!take.observed[f][m].allFinite()) continue;
      const double e = (take.markers.Position(m, fk) - take.observed[f][m]).norm() * scale;
      sum += e * e;
      worst = std::max(worst, e);
      ++count;
    }
    char line[160];
    std::snprintf(line, sizeof(line), "%d,%.6g,%d,%.6g,%.6g\n", f, rate > 0 ? f / rate : 0.0, count,
                  count > 0 ? std::sqrt(sum / count) : 0.0, worst);
    csv += line;
  }
  return csv;
}

}  // namespace mocapsolve
