#include "apps/bench_problems.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <iomanip>
#include <map>
#include <random>
#include <sstream>

#include <unistd.h>

#include <ceres/iteration_callback.h>

#include "apps/common_flags.h"
#include "apps/corruption_flags.h"
#include "apps/repair_flags.h"
#include "apps/solver_flags.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/gltf_reader.h"
#include "io/motion_file.h"
#include "apps/retarget_flags.h"
#include "problems/retarget/retarget_character.h"
#include "pipeline/take_pipeline.h"
#include "problems/marker_repair/marker_repair.h"
#include "problems/marker_solve/marker_observations.h"
#include "problems/marker_solve/sequence_solver.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/kinematic_jacobians.h"
#include "kinematics/rotation.h"
#include "signal/laplacian_pyramid.h"

namespace mocapsolve {

// LoadMotion: apps/common_flags.h.

JsonObject BenchRecord::ToJson() const {
  JsonObject json;
  json.Add("problem", problem).Add("solver", solver).Add("input", input).Add("frames", frames)
      .Add("seconds", seconds).Add("frames_per_second", frames_per_second())
      .Add("iterations", iterations).Add("final_cost", final_cost)
      .Add(error_name.empty() ? "error" : error_name, error).Add("notes", notes);
  for (const auto& [name, value] : figures) json.Add(name, value);
  return json;
}

namespace {

// CPU seconds of the process (all threads): the figure to compare on a loaded machine.
double ProcessCpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

template <typename Function>
double MedianSeconds(int repeats, Function&& function) {
  std::vector<double> times;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    const auto start = std::chrono::steady_clock::now();
    function();
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

// FK of every frame of a clip: the kinematic core's throughput.
Status RunFkProblem(const std::string& solver, const BenchSettings& settings, BenchRecord* record) {
  if (solver != "fk") return Status::Error("problem fk has one solver, 'fk'");
  Skeleton skeleton;
  Motion motion;
  if (settings.motion_path.empty()) {
    skeleton = MakeDemoSkeleton();
    motion = MakeDemoWalk(skeleton, 2400, 120.0);
    record->input = "procedural demo walk";
  } else {
    Status status = LoadMotion(settings.motion_path, &skeleton, &motion);
    if (!status.ok()) return status;
    record->input = settings.motion_path;
  }
  FkData data(skeleton);
  double checksum = 0.0;
  const int passes = std::max(1, 200000 / std::max(1, motion.num_frames()));
  record->seconds = MedianSeconds(settings.repeats, [&] {
    for (int pass = 0; pass < passes; ++pass) {
      for (const Pose& pose : motion.frames) {
        ForwardKinematics(skeleton, pose, &data);
        checksum += data.world_positions.back().x();
      }
    }
  });
  record->frames = passes * motion.num_frames();
  record->error_name = "checksum";  // Keeps the work observable; not an accuracy figure.
  record->error = checksum;
  return Status::Ok();
}

// Seconds per frame of FK plus the full dense Jacobian of every marker (3 #markers x
// (3 + 3 #J), pose tangent layout of kinematics/kinematic_jacobians.h): the unit in which
// issue 18 states the per-frame IK's cost. The lean way: ForwardKinematics, then
// MarkerSetJacobian (kinematics/marker_set.h). Over the clip's poses, repeated to >= 20,000
// frames.
double FkAndMarkerJacobianSeconds(const Skeleton& skeleton, const MarkerSet& markers, const Motion& motion) {
  FkData fk(skeleton);
  Eigen::MatrixXd jacobian;
  std::vector<Eigen::Matrix3d> rotations;
  double checksum = 0.0;
  const int passes = std::max(1, 20000 / std::max(1, motion.num_frames()));
  const auto start = std::chrono::steady_clock::now();
  for (int pass = 0; pass < passes; ++pass) {
    for (const Pose& pose : motion.frames) {
      ForwardKinematics(skeleton, pose, &fk);
      MarkerSetJacobian(skeleton, markers, fk, &rotations, &jacobian);
      checksum += jacobian(jacobian.rows() - 1, 3);
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (checksum == 12345.678) std::printf(" ");  // Keeps the work observable.
  return seconds / (static_cast<double>(passes) * std::max(1, motion.num_frames()));
}

// The marker problem of a benchmark: real files, or markers synthesized from a clip.
Status LoadMarkerProblem(const BenchSettings& settings, Skeleton* skeleton_out, MarkerSet* markers_out,
                         std::vector<std::vector<Eigen::Vector3d>>* observed_out, BenchRecord* record) {
  Skeleton& skeleton = *skeleton_out;
  MarkerSet& markers = *markers_out;
  std::vector<std::vector<Eigen::Vector3d>>& observed = *observed_out;
  if (!settings.markers_path.empty()) {
    Status status = LoadSkeleton(settings.skeleton_path, &skeleton);
    if (status.ok()) status = ReadMarkerSet(settings.markerset_path, skeleton, &markers);
    MarkerTrajectories trajectories;
    MarkerFileToModel transform;
    if (status.ok()) {
      status = LoadObservations(settings.markers_path, skeleton, markers, &trajectories, &transform, &observed);
    }
    if (!status.ok()) return status;
    record->input = settings.markers_path;
  } else {
    Motion motion;
    if (settings.motion_path.empty()) {
      skeleton = MakeDemoSkeleton();
      motion = MakeDemoWalk(skeleton, 600, 120.0);
      record->input = "procedural demo walk, 3 synthetic markers per joint";
    } else {
      Status status = LoadMotion(settings.motion_path, &skeleton, &motion);
      if (!status.ok()) return status;
      record->input = settings.motion_path + ", 3 synthetic markers per joint";
    }
    markers = MakeSyntheticMarkerSet(skeleton, 3, 1);
    FkData fk(skeleton);
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 1.0);
    const double sigma = settings.noise_mm > 0.0 && skeleton.unit().known()
                             ? settings.noise_mm / (1000.0 * skeleton.unit().metres_per_unit)
                             : 0.0;
    for (const Pose& pose : motion.frames) {
      ForwardKinematics(skeleton, pose, &fk);
      observed.emplace_back();
      for (int m = 0; m < markers.num_markers(); ++m) {
        observed.back().push_back(markers.Position(m, fk) +
                                  sigma * Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
      }
    }
    if (sigma > 0.0) record->input += ", " + std::to_string(settings.noise_mm) + " mm noise";
  }
  if (settings.max_frames > 0 && static_cast<int>(observed.size()) > settings.max_frames) {
    observed.resize(settings.max_frames);
  }
  return Status::Ok();
}

// Per-frame marker solving of a take, warm-started frame to frame. Real markers with
// --bench_skeleton/--bench_markers/--bench_markerset (marker axes/scale flags as for
// solve), else noise-free markers synthesized from a clip (3 per joint). The solver
// flags (--max_iterations, tolerances, --loss, ...) apply to both solvers alike; the
// first frame's orientation search is not timed.
Status RunMarkerSolveProblem(const std::string& solver, const BenchSettings& settings,
                             BenchRecord* record) {
  SolverKind kind;
  if (!ParseSolverKind(solver, &kind)) return Status::Error("marker_solve solvers: ceres, dls, dls_generic");
  Skeleton skeleton;
  MarkerSet markers;
  std::vector<std::vector<Eigen::Vector3d>> observed;
  double mm_per_unit = 0.0;
  Status load = LoadMarkerProblem(settings, &skeleton, &markers, &observed, record);
  if (!load.ok()) return load;
  if (skeleton.unit().known()) mm_per_unit = skeleton.unit().metres_per_unit * 1000.0;
  MarkerSolveOptions options;
  Status status = MarkerSolveOptionsFromFlags(skeleton.unit(), &options);
  if (!status.ok()) return status;
  options.solver = kind;
  Motion solved;
  SequenceSolveReport report;
  std::vector<double> times, reference_times;
  for (int r = 0; r < std::max(1, settings.repeats); ++r) {
    status = SolveSequence(skeleton, markers, observed, options, RestPose(skeleton), &solved, &report);
    if (!status.ok()) return status;
    times.push_back(report.solve_seconds);
    // The reference, interleaved with the solves: one FK plus the full marker Jacobian
    // (3 #markers x (3 + 3 #joints), kinematics/kinematic_jacobians.h) per frame.
    reference_times.push_back(FkAndMarkerJacobianSeconds(skeleton, markers, solved));
  }
  std::sort(times.begin(), times.end());
  std::sort(reference_times.begin(), reference_times.end());
  record->seconds = times[times.size() / 2];
  record->frames = report.frames;
  record->iterations = static_cast<int>(report.total_iterations);
  record->final_cost = report.total_final_cost;
  record->error_name = mm_per_unit > 0 ? "rms_marker_residual_mm" : "rms_marker_residual";
  record->error = report.rms_marker_error * (mm_per_unit > 0 ? mm_per_unit : 1.0);
  record->notes = std::to_string(markers.num_markers()) + " markers; unsolved frames " +
                  std::to_string(report.unsolved_frames) + ", at iteration limit " +
                  std::to_string(report.unconverged_frames);
  const double per_frame = record->seconds / std::max(1, record->frames);
  const double reference = reference_times[reference_times.size() / 2];
  record->figures = {{"us_per_frame", 1e6 * per_frame},
                     {"fk_jacobian_us", 1e6 * reference},
                     {"ratio_to_fk_jacobian", per_frame / reference}};
  return Status::Ok();
}

// Ceres' counterpart of DlsOptions::absolute_cost_tolerance: stop once the cost is <= target.
class StopAtCost : public ceres::IterationCallback {
 public:
  explicit StopAtCost(double target) : target_(target) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    return summary.cost <= target_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
  }

 private:
  double target_;
};

// The clip problem of a bench process, loaded and given its initial guess once for all
// solvers, and each solver's converged cost (the equal-cost target needs both).
struct ClipBenchState {
  std::string key;
  Skeleton skeleton;
  MarkerSet markers;
  std::vector<std::vector<Eigen::Vector3d>> observed;
  Motion initial;
  std::string input;
  std::map<std::string, ClipSolveReport> converged;
  std::map<std::string, double> converged_cpu;
};

// ceres | dls (block-banded) | dls_ldlt (the DLS on Eigen's SimplicialLDLT), from the flags.
Status ClipOptionsForSolver(const std::string& solver, ClipSolveOptions* options) {
  Status status = ClipSolveOptionsFromFlags(options);
  if (!status.ok()) return status;
  options->solver = solver == "ceres" ? "ceres" : "dls";
  options->dls_linear_solver =
      solver == "dls_ldlt" ? DlsLinearSolver::kSparseLdlt : DlsLinearSolver::kBlockBanded;
  return Status::Ok();
}

// The whole-clip solve: per-frame DLS for the initial guess (not timed), then all frames
// as one sparse problem with smoothness. Markers as for marker_solve, with
// --bench_noise_mm of Gaussian noise added to synthesized ones. Solvers ceres, dls
// (block-banded) and dls_ldlt are compared at equal final cost: ceres and dls first run
// to convergence once (untimed; their CPU time is reported as converged_cpu_seconds),
// the target is the higher of the two final costs times (1 + 1e-6), and the timed runs
// stop as soon as their cost is at or below it (Ceres through an IterationCallback, DLS
// through absolute_cost_tolerance).
Status RunMarkerClipProblem(const std::string& solver, const BenchSettings& settings,
                            BenchRecord* record) {
  if (solver != "ceres" && solver != "dls" && solver != "dls_ldlt") {
    return Status::Error("marker_clip solvers: ceres, dls, dls_ldlt");
  }
  static ClipBenchState state;
  const std::string key = settings.motion_path + "|" + settings.markers_path + "|" +
                          std::to_string(settings.max_frames) + "|" + std::to_string(settings.noise_mm);
  if (state.key != key) {
    state = ClipBenchState();
    BenchRecord loaded;
    Status status = LoadMarkerProblem(settings, &state.skeleton, &state.markers, &state.observed, &loaded);
    if (!status.ok()) return status;
    state.input = loaded.input;
    MarkerSolveOptions frame_options;
    status = MarkerSolveOptionsFromFlags(state.skeleton.unit(), &frame_options);
    if (!status.ok()) return status;
    frame_options.solver = SolverKind::kDls;
    SequenceSolveReport sequence;
    status = SolveSequence(state.skeleton, state.markers, state.observed, frame_options,
                           RestPose(state.skeleton), &state.initial, &sequence);
    if (!status.ok()) return status;
    state.key = key;
  }
  record->input = state.input;
  for (const std::string& reference : {std::string("ceres"), std::string("dls")}) {
    if (state.converged.count(reference) != 0) continue;
    ClipSolveOptions options;
    Status status = ClipOptionsForSolver(reference, &options);
    if (!status.ok()) return status;
    Motion motion = state.initial;
    const double cpu = ProcessCpuSeconds();
    status = SolveClip(state.skeleton, state.markers, state.observed, options, &motion, &state.converged[reference]);
    if (!status.ok()) return status;
    state.converged_cpu[reference] = ProcessCpuSeconds() - cpu;
  }
  const double target =
      std::max(state.converged["ceres"].final_cost, state.converged["dls"].final_cost) * (1.0 + 1e-6);

  ClipSolveOptions options;
  Status status = ClipOptionsForSolver(solver, &options);
  if (!status.ok()) return status;
  StopAtCost stop(target);
  options.ceres.callbacks.push_back(&stop);
  options.dls.absolute_cost_tolerance = target;
  std::vector<double> times, cpu_times, linear_times;
  ClipSolveReport report;
  for (int r = 0; r < std::max(1, settings.repeats); ++r) {
    Motion motion = state.initial;
    const double cpu = ProcessCpuSeconds();
    status = SolveClip(state.skeleton, state.markers, state.observed, options, &motion, &report);
    if (!status.ok()) return status;
    cpu_times.push_back(ProcessCpuSeconds() - cpu);
    times.push_back(report.solve_seconds);
    linear_times.push_back(report.linear_solve_seconds);
  }
  const double mm = state.skeleton.unit().known() ? state.skeleton.unit().metres_per_unit * 1000.0 : 0.0;
  record->seconds = Median(times);
  record->frames = static_cast<int>(state.observed.size());
  record->iterations = report.iterations;
  record->final_cost = report.final_cost;
  record->error_name = mm > 0 ? "rms_marker_residual_mm" : "rms_marker_residual";
  record->error = report.rms_marker_error * (mm > 0 ? mm : 1.0);
  const ClipSolveReport& own = state.converged[solver == "ceres" ? "ceres" : "dls"];
  record->notes = std::to_string(report.parameters) + " parameters, " +
                  std::to_string(report.residual_blocks) + " residual blocks; initial guess: " +
                  "per-frame DLS (untimed); stopped at the equal-cost target; " + report.brief;
  record->figures = {{"cpu_seconds", Median(cpu_times)},
                     {"linear_solve_seconds", Median(linear_times)},
                     {"target_cost", target},
                     {"converged_cost", own.final_cost},
                     {"converged_iterations", static_cast<double>(own.iterations)},
                     {"converged_cpu_seconds", state.converged_cpu[solver == "ceres" ? "ceres" : "dls"]}};
  if (report.factorization_flops > 0) {
    record->figures.push_back({"factorization_gflop", 1e-9 * report.factorization_flops});
  }
  return Status::Ok();
}

// Retargeting a clip onto a character, as `mocapsolve retarget` and the pipeline do it
// (RetargetMotionOntoCharacter with the retarget flags): source --bench_motion (a motion
// file; the target's mesh is bound to its skeleton), target the one --bench_character
// (.glb); --bench_frames. Timed: the frame loop (seconds, wall) and the whole call
// including the setup (cpu_seconds); error: mean tracked-vertex error / target height.
Status RunRetargetProblem(const std::string& solver, const BenchSettings& settings, BenchRecord* record) {
  if (solver != "dls" && solver != "dls_generic" && solver != "ceres") {
    return Status::Error("retarget solvers: dls, dls_generic, ceres");
  }
  if (settings.motion_path.empty() || settings.character_paths.size() != 1) {
    return Status::Error("retarget: --bench_motion (the source clip) and one --bench_character (the target .glb) are required");
  }
  Skeleton source_skeleton;
  Motion clip;
  Status status = LoadMotion(settings.motion_path, &source_skeleton, &clip);
  if (!status.ok()) return status;
  if (settings.max_frames > 0 && clip.num_frames() > settings.max_frames) clip.frames.resize(settings.max_frames);
  GltfCharacter target;
  status = ReadGltfCharacter(settings.character_paths[0], GltfReadOptions(), &target);
  if (!status.ok()) return status;
  const std::string given = gflags::GetCommandLineFlagInfoOrDie("solver").current_value;
  gflags::SetCommandLineOption("solver", solver.c_str());
  CharacterRetargetOptions options;
  status = RetargetOptionsFromFlags(&options);
  gflags::SetCommandLineOption("solver", given.c_str());
  if (!status.ok()) return status;
  RetargetCharacter source_view;
  source_view.skeleton = &source_skeleton;
  const RetargetCharacter target_view = {&target.skeleton, &target.mesh, target.bind_pose, target.rest_pose};
  std::vector<double> times, cpu_times;
  CharacterRetargetResult result;
  for (int r = 0; r < std::max(1, settings.repeats); ++r) {
    const double cpu = ProcessCpuSeconds();
    status = RetargetMotionOntoCharacter(source_view, clip, target_view, options, &result);
    if (!status.ok()) return status;
    cpu_times.push_back(ProcessCpuSeconds() - cpu);
    times.push_back(result.clip.solve_seconds);
  }
  int iterations = 0;
  for (const RetargetFrameFigures& f : result.clip.frames) iterations += f.iterations;
  record->input = settings.motion_path + " onto " + settings.character_paths[0];
  record->seconds = Median(times);
  record->frames = clip.num_frames();
  record->iterations = iterations;
  record->final_cost = result.clip.mean_final_cost;
  record->error_name = "mean_vertex_error_per_height";
  record->error = result.clip.mean_position_error;
  record->notes = std::to_string(result.setup.tracked.size()) + " tracked vertices; seconds: the frame loop; "
                  "cpu_seconds: the whole call with its setup";
  record->figures = {{"cpu_seconds", Median(cpu_times)},
                     {"ms_per_frame", 1e3 * record->seconds / std::max(1, record->frames)}};
  return Status::Ok();
}

// Marker repair (issue 4) of a damaged take: markers as for marker_solve, damaged with
// the corruption flags (--gaps, --swaps, ...; seed --seed), repaired with the
// repair flags; the solver is the reference kind (tracker or clip). Timed: the whole
// RepairMarkers call; the notes give the stages of the median run (thesis Table 2).
Status RunMarkerRepairProblem(const std::string& solver, const BenchSettings& settings,
                              BenchRecord* record) {
  if (solver != "tracker" && solver != "clip") return Status::Error("marker_repair solvers: tracker, clip");
  Skeleton skeleton;
  MarkerSet markers;
  std::vector<std::vector<Eigen::Vector3d>> observed;
  Status status = LoadMarkerProblem(settings, &skeleton, &markers, &observed, record);
  if (!status.ok()) return status;
  RepairOptions options;
  status = RepairOptionsFromFlags(skeleton, &options);
  CorruptionOptions damage;
  if (status.ok()) status = CorruptionOptionsFromFlags(skeleton.unit(), &damage);
  if (!status.ok()) return status;
  options.reference_kind = solver == "tracker" ? ReferenceKind::kTracker : ReferenceKind::kClip;
  MarkerTrajectories x = ObservationTrajectories(markers, observed);
  CorruptionMask mask;
  CorruptMarkers(damage, &x, &mask);
  const auto corrupted = TrajectoryObservations(x);
  std::vector<std::pair<double, RepairReport>> runs;
  for (int r = 0; r < std::max(1, settings.repeats); ++r) {
    std::vector<std::vector<Eigen::Vector3d>> repaired;
    Motion motion;
    RepairReport report;
    const auto start = std::chrono::steady_clock::now();
    status = RepairMarkers(skeleton, markers, corrupted, options, &repaired, &motion, &report);
    if (!status.ok()) return status;
    runs.push_back({std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), report});
  }
  std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const auto& [seconds, report] = runs[runs.size() / 2];
  const double mm = skeleton.unit().known() ? skeleton.unit().metres_per_unit * 1000.0 : 1.0;
  record->seconds = seconds;
  record->frames = static_cast<int>(observed.size());
  record->error_name = "rms_repaired_marker_residual_mm";
  record->error = report.repaired_rms * mm;
  std::string stages;
  for (const RepairStageTime& t : report.timings) {
    char text[160];
    std::snprintf(text, sizeof(text), "%s%s %.1f%%", stages.empty() ? "" : "; ", t.stage.c_str(),
                  seconds > 0 ? 100.0 * t.seconds / seconds : 0.0);
    stages += text;
  }
  record->notes = std::to_string(markers.num_markers()) + " markers, " + std::to_string(report.detected.size()) +
                  " intervals detected, " + std::to_string(report.resolved_frames) + " frames re-solved; " + stages;
  return Status::Ok();
}

// Build + reconstruct of a Laplacian pyramid (issue 7): a 10,000-frame, 96-channel
// synthetic clip (--bench_frames overrides the length), every level, buffers reused as
// an editing loop would; error = max |reconstruction - input| (the exactness check).
Status RunPyramidProblem(const std::string& solver, const BenchSettings& settings,
                         BenchRecord* record) {
  if (solver != "pyramid") return Status::Error("problem pyramid has one solver, 'pyramid'");
  const int frames = settings.max_frames > 0 ? settings.max_frames : 10000;
  if (frames < 3) return Status::Error("--bench_frames: a pyramid needs at least 3 frames");
  const int channels = 96;
  Signal signal(frames, channels);
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int f = 0; f < frames; ++f) {
    for (int c = 0; c < channels; ++c) {
      signal(f, c) = std::sin(0.01 * f * (1 + c % 7) + c) + 0.001 * f + noise(rng);
    }
  }
  LaplacianPyramid pyramid;
  Signal out, scratch;
  // One untimed pass allocates every buffer.
  Status status = BuildLaplacianPyramid(signal, PyramidOptions(), &pyramid);
  if (!status.ok()) return status;
  ReconstructSignal(pyramid, {}, &out, &scratch);
  record->seconds = MedianSeconds(std::max(settings.repeats, 11), [&] {
    status = BuildLaplacianPyramid(signal, PyramidOptions(), &pyramid);
    ReconstructSignal(pyramid, {}, &out, &scratch);
  });
  if (!status.ok()) return status;
  record->input = "synthetic " + std::to_string(frames) + " x " + std::to_string(channels);
  record->frames = frames;
  record->error_name = "max_reconstruction_error";
  record->error = (out - signal).cwiseAbs().maxCoeff();
  record->notes = std::to_string(pyramid.levels()) + " levels, kernel a = 0.4, Catmull-Rom EXPAND";
  return Status::Ok();
}

}  // namespace

// One take end to end (pipeline/take_pipeline.h), outputs kept in memory: read, repair
// and solve, retarget onto each character, the gate. The solver runs both the marker
// solves and the retarget's per-frame solves. Notes: the stages of the median run.
Status RunPipelineProblem(const std::string& solver, const BenchSettings& settings, BenchRecord* record) {
  if (solver != "dls" && solver != "ceres") return Status::Error("pipeline solvers: dls, ceres");
  if (settings.subject_path.empty() || settings.markers_path.empty()) {
    return Status::Error("pipeline: --bench_subject and --bench_markers are required");
  }
  Subject subject;
  Status status = ReadSubject(settings.subject_path, &subject);
  if (!status.ok()) return status;
  const std::string given = gflags::GetCommandLineFlagInfoOrDie("solver").current_value;
  gflags::SetCommandLineOption("solver", solver.c_str());
  TakePipelineOptions options;
  status = RepairOptionsFromFlags(subject.skeleton, &options.repair);
  if (status.ok()) status = RetargetOptionsFromFlags(&options.retarget);
  gflags::SetCommandLineOption("solver", given.c_str());
  if (!status.ok()) return status;
  TakeInputs inputs;
  inputs.name = "bench";
  inputs.subject = &subject;
  inputs.markers_path = settings.markers_path;
  inputs.character_paths = settings.character_paths;
  std::vector<std::pair<double, TakeResult>> runs;
  for (int r = 0; r < std::max(1, settings.repeats); ++r) {
    TakeResult result;
    status = RunTakePipeline(inputs, options, &result);
    if (!status.ok()) return status;
    runs.push_back({result.seconds, std::move(result)});
  }
  std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const TakeResult& median = runs[runs.size() / 2].second;
  record->input = settings.markers_path + " onto " + std::to_string(settings.character_paths.size()) + " character(s)";
  record->seconds = median.seconds;
  record->frames = static_cast<int>(median.take.observed.size());
  record->error_name = "rms_repaired_marker_residual_mm";
  record->error = median.figures.repaired_rms_mm;
  std::ostringstream notes;
  for (const StageTime& t : median.timings) {
    notes << t.stage << " " << std::fixed << std::setprecision(3) << t.seconds << " s; ";
  }
  record->notes = notes.str();
  return Status::Ok();
}

// Our kinematics beside Orocos KDL, MuJoCo and DART (issue 18): runs
// bench/peers' mocapsolve_peers_bench, built beside this binary when a peer library was
// found, in its interleaved mode (--repeats rounds; --bench_motion, --bench_frames = IK
// frames), passes its table through and keeps its "PEERS name value" figures.
Status RunPeersProblem(const std::string& solver, const BenchSettings& settings, BenchRecord* record) {
  if (solver != "all") return Status::Error("problem peers has one solver, 'all'");
  char self[4096];
  const ssize_t length = readlink("/proc/self/exe", self, sizeof(self) - 1);
  std::string dir = length > 0 ? std::string(self, length) : std::string("./mocapsolve");
  dir = dir.substr(0, dir.rfind('/') == std::string::npos ? 0 : dir.rfind('/'));
  const std::string program = (dir.empty() ? "." : dir) + "/mocapsolve_peers_bench";
  if (access(program.c_str(), X_OK) != 0) {
    return Status::Error("problem peers: " + program + " is not built; install the peer libraries and rebuild "
                         "(scripts/setup.sh --with-peers)");
  }
  std::string command = "'" + program + "' --interleaved --rounds=" + std::to_string(std::max(1, settings.repeats));
  if (!settings.motion_path.empty()) command += " --motion='" + settings.motion_path + "'";
  if (settings.max_frames > 0) command += " --ik_frames=" + std::to_string(settings.max_frames);
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return Status::Error("problem peers: cannot run " + program);
  char line[4096];
  std::string last;
  while (std::fgets(line, sizeof(line), pipe) != nullptr) {
    std::string text(line);
    if (text.rfind("PEERS ", 0) == 0) {
      std::istringstream fields(text.substr(6));
      std::string name;
      double value = 0.0;
      if (fields >> name >> value) record->figures.push_back({name, value});
      continue;
    }
    std::fputs(line, stdout);
    if (text.find_first_not_of(" \n") != std::string::npos) last = text.substr(0, text.find('\n'));
  }
  const int code = pclose(pipe);
  if (code != 0) return Status::Error("problem peers: mocapsolve_peers_bench failed: " + last);
  record->input = settings.motion_path.empty() ? "CMU 01_01 (bvh/01_01.bvh), 93 synthetic markers" : settings.motion_path;
  record->error_name = "figures";
  record->error = static_cast<double>(record->figures.size());
  record->notes = "per-frame CPU-time medians of interleaved rounds; ratios peer / ours (see the table above)";
  return Status::Ok();
}

const std::vector<BenchProblem>& AllBenchProblems() {
  static const std::vector<BenchProblem> problems = {
      {"fk", "forward kinematics of every frame of a clip (--motion, default: demo walk)",
       {"fk"}, RunFkProblem},
      {"marker_clip", "whole-clip marker solve as one sparse problem (inputs as for "
       "marker_solve; --bench_noise_mm for synthesized markers); Ceres vs the block-banded DLS "
       "(and DLS on Eigen's sparse LDLT) timed to an equal final cost",
       {"ceres", "dls", "dls_ldlt"}, RunMarkerClipProblem},
      {"retarget", "a clip onto a character as `mocapsolve retarget` (--bench_motion source, "
       "--bench_character target .glb, retarget flags, --bench_frames)",
       {"dls", "dls_generic", "ceres"}, RunRetargetProblem},
      {"marker_solve", "per-frame marker solving of a take (--bench_markers/--bench_skeleton/"
       "--bench_markerset, or markers synthesized from --bench_motion)",
       {"dls", "dls_generic", "ceres"}, RunMarkerSolveProblem},
      {"marker_repair", "marker repair of a damaged take (markers as for marker_solve; damage from "
       "the corrupt flags; repair flags as for repair); solvers = reference kinds",
       {"tracker", "clip"}, RunMarkerRepairProblem},
      {"pipeline", "one take end to end in memory (--bench_subject, --bench_markers, "
       "--bench_character): repair and solve, retarget, gate; solver = the per-frame solver",
       {"dls", "ceres"}, RunPipelineProblem},
      {"peers", "our FK, Jacobian and marker IK beside Orocos KDL, MuJoCo and DART (runs "
       "mocapsolve_peers_bench, built with scripts/setup.sh --with-peers)",
       {"all"}, RunPeersProblem},
      {"pyramid", "Laplacian pyramid build + reconstruct of a 10,000 x 96 synthetic clip "
       "(--bench_frames for another length)",
       {"pyramid"}, RunPyramidProblem},
  };
  return problems;
}

}  // namespace mocapsolve
