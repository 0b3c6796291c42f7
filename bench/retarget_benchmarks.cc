// Mesh retargeting benchmarks (issue 5, thesis Tables 3 and 4), Google Benchmark.
//   build/bin/mocapsolve_bench --benchmark_filter=Retarget [--benchmark_format=json]
//
// Each case is set up once (subsampling, mapping, goals of a looped source clip); a
// benchmark iteration solves the next frame of the loop, warm-started from the previous
// one, as RetargetClip does (5 iterations a frame, thesis Table 4; lambda 5). So the
// time per iteration is the time per frame; "s_per_4000_frames" extrapolates it to the
// thesis' 4000-frame clip (43.5 / 48.9 / 58.9 s at 128:1 / 64:1 / 32:1, i.e. 10.9 ms a
// frame at 128:1; our target <= 0.5 ms a frame at 128:1 for DLS). "vertex_error" is the
// mean tracked-vertex error (fraction of the target height) over 100 frames solved the
// same way after the timing, so the solvers can be compared at equal error.
// Cases: a synthetic cylinder character (~19k vertices, demo skeleton, 20 joints) onto a
// 0.8-scaled copy, and glTF pairs from MOCAPSOLVE_DATA (default ../shared/data; skipped
// with an error without it): Soldier "Walk" -> Xbot (49 -> 65 joints) and CesiumMan ->
// RiggedFigure (19 -> 19 joints, different names and proportions).
// BM_RetargetSkeletonOnly: a whole skeleton-only clip through RetargetMotionOntoCharacter
// (retarget_character.h): CMU 16_15 (BVH, cm; 120 frames) onto Xbot, feet planted (1) or
// not (0); one benchmark iteration = one call (binding, setup and the frame loop).
// BM_RetargetStages: the share of FK, skinning, Jacobian (normal-equation assembly) and
// the linear solve in one DLS iteration (thesis Table 3), from RetargetSolveOptions::
// time_stages.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include <benchmark/benchmark.h>

#include "io/gltf_reader.h"
#include "io/motion_file.h"
#include "kinematics/demo_character.h"
#include "problems/retarget/retarget_character.h"
#include "problems/retarget/retarget_clip.h"
#include "problems/retarget/retarget_frame_solver.h"
#include "problems/retarget/retarget_setup.h"
#include "problems/retarget/synthetic_skinned_character.h"

namespace mocapsolve {
namespace {

std::string GltfFile(const std::string& name) {
  const char* env = std::getenv("MOCAPSOLVE_DATA");
  const std::string root = env != nullptr && *env ? env : MOCAPSOLVE_SOURCE_DIR "/../shared/data";
  return root + "/gltf/" + name;
}

struct Character {
  Skeleton skeleton;
  SkinnedMesh mesh;
  Pose start;  // Warm start of frame 0.
  Eigen::Matrix3d world_from_bind = Eigen::Matrix3d::Identity();
};

struct Case {
  Status status = Status::Error("not loaded");
  Character source, target;
  RetargetSetup setup;
  RetargetGoals goals;  // Of the looped clip.
};

constexpr int kLoopFrames = 400;  // Goals precomputed for this many frames of the loop.

Status LoadGltf(const std::string& file, Character* character, GltfDocument* document,
                GltfCharacter* gltf) {
  Status status = GltfDocument::Read(GltfFile(file), document);
  if (!status.ok()) return status;
  status = ReadGltfCharacter(*document, GltfReadOptions(), gltf);
  if (!status.ok()) return status;
  character->skeleton = gltf->skeleton;
  character->mesh = gltf->mesh;
  character->start = gltf->rest_pose;
  character->world_from_bind = WorldFromBindRotation(gltf->skeleton, gltf->bind_pose, gltf->rest_pose);
  return Status::Ok();
}

Motion Loop(const Motion& clip, int frames) {
  Motion looped;
  looped.frame_rate = clip.frame_rate;
  for (int f = 0; f < frames; ++f) looped.frames.push_back(clip.frames[f % clip.num_frames()]);
  return looped;
}

Status Finish(Case* c, const Motion& source_motion, int ratio) {
  RetargetSetupOptions options;
  options.subsample.ratio = ratio;
  options.source_world_from_bind = c->source.world_from_bind;
  options.target_world_from_bind = c->target.world_from_bind;
  Status status = BuildRetargetSetup(c->source.mesh, c->target.skeleton, c->target.mesh, options, &c->setup);
  if (!status.ok()) return status;
  ComputeRetargetGoals(c->setup, c->source.skeleton, c->source.mesh, Loop(source_motion, kLoopFrames), &c->goals);
  return Status::Ok();
}

// 0: synthetic, 1: Soldier Walk -> Xbot, 2: CesiumMan -> RiggedFigure.
const Case& GetCase(int which, int ratio) {
  static std::map<std::pair<int, int>, std::unique_ptr<Case>> cache;
  auto& slot = cache[{which, ratio}];
  if (slot) return *slot;
  slot.reset(new Case);
  Case* c = slot.get();
  if (which == 0) {
    CylinderCharacterOptions mesh_options;
    mesh_options.segments = 24;
    mesh_options.rings = 40;
    c->source.skeleton = MakeDemoSkeleton();
    c->source.mesh = MakeCylinderCharacter(c->source.skeleton, mesh_options);
    c->source.start = RestPose(c->source.skeleton);
    c->target.skeleton = ScaleSkeleton(c->source.skeleton, 0.8);
    c->target.mesh = MakeCylinderCharacter(c->target.skeleton, mesh_options);
    c->target.start = RestPose(c->target.skeleton);
    const Motion walk = MakeDemoWalk(c->source.skeleton, 33, 30.0);  // One 1.1 s cycle.
    c->status = Finish(c, walk, ratio);
    return *c;
  }
  const char* source_file = which == 1 ? "Soldier.glb" : "CesiumMan.glb";
  const char* animation = which == 1 ? "Walk" : "";
  const char* target_file = which == 1 ? "Xbot.glb" : "RiggedFigure.glb";
  GltfDocument source_document, target_document;
  GltfCharacter source_gltf, target_gltf;
  c->status = LoadGltf(source_file, &c->source, &source_document, &source_gltf);
  if (c->status.ok()) c->status = LoadGltf(target_file, &c->target, &target_document, &target_gltf);
  if (!c->status.ok()) return *c;
  GltfAnimationOptions animation_options;
  animation_options.animation = animation;
  Motion clip;
  c->status = ReadGltfAnimation(source_document, source_gltf, animation_options, &clip);
  if (c->status.ok()) c->status = Finish(c, clip, ratio);
  return *c;
}

Pose StartPose(const Case& c) {
  return RecenteredStartPose(c.target.skeleton, c.target.mesh, c.setup, c.goals.positions[0], c.target.start);
}

void RunFrames(benchmark::State& state, int which) {
  const int ratio = static_cast<int>(state.range(0));
  const SolverKind kind = static_cast<SolverKind>(state.range(1));
  const Case& c = GetCase(which, ratio);
  if (!c.status.ok()) return state.SkipWithError(c.status.message().c_str());
  RetargetSolveOptions options;
  options.solver = kind;
  options.iterations = 5;
  options.lambda = 5.0;
  options.ceres = DefaultRetargetCeresOptions();
  options.ceres.initial_trust_region_radius = std::pow(10.0, static_cast<double>(state.range(2)));
  RetargetFrameSolver solver(c.target.skeleton, c.target.mesh, c.setup, c.goals.sigma, options);
  // Settle into the loop (frame 0 starts from the rest pose), untimed.
  Pose pose = StartPose(c);
  for (int f = 0; f < 20; ++f) (void)solver.Solve(c.goals.positions[f], c.goals.normals[f], &pose, nullptr);
  int f = 20;
  for (auto _ : state) {
    const Status status = solver.Solve(c.goals.positions[f], c.goals.normals[f], &pose, nullptr);
    if (!status.ok()) return state.SkipWithError(status.message().c_str());
    benchmark::DoNotOptimize(pose.rotations.data());
    if (++f == kLoopFrames) f = 0;
  }
  // Quality at the same settings, untimed: 100 frames from where the loop stands.
  double error = 0.0, angle = 0.0;
  for (int k = 0; k < 100; ++k) {
    RetargetFrameReport report;
    (void)solver.Solve(c.goals.positions[f], c.goals.normals[f], &pose, &report);
    error += report.mean_position_error / c.setup.target_frame.height / 100.0;
    angle += report.mean_normal_angle * 57.29577951308232 / 100.0;
    if (++f == kLoopFrames) f = 0;
  }
  // The case in words (the arguments are codes): solver, and Ceres' trust radius.
  state.SetLabel(std::string(SolverKindName(kind)) + ", 1:" + std::to_string(state.range(0)) + " vertices" +
                 (kind == SolverKind::kCeres ? ", trust radius 1e" + std::to_string(state.range(2)) : ""));
  state.counters["tracked"] = static_cast<double>(c.setup.tracked.size());
  state.counters["joints"] = c.target.skeleton.num_joints();
  state.counters["vertex_error"] = error;
  state.counters["normal_error_deg"] = angle;
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["s_per_4000_frames"] = benchmark::Counter(
      static_cast<double>(state.iterations()) / 4000.0, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_RetargetSynthetic(benchmark::State& state) { RunFrames(state, 0); }
void BM_RetargetSoldierToXbot(benchmark::State& state) { RunFrames(state, 1); }
void BM_RetargetCesiumManToRiggedFigure(benchmark::State& state) { RunFrames(state, 2); }

void RatiosAndSolvers(benchmark::internal::Benchmark* b) {
  // solver 0 = dls, 2 = ceres; radius = log10 of Ceres' initial trust region (4: its
  // default, 0: radius 1, which the retarget command uses).
  for (int ratio : {128, 64, 32}) {
    b->Args({ratio, static_cast<int>(SolverKind::kDls), 0});
    b->Args({ratio, static_cast<int>(SolverKind::kCeres), 4});
    b->Args({ratio, static_cast<int>(SolverKind::kCeres), 0});
  }
  b->ArgNames({"ratio", "solver", "radius"})->Unit(benchmark::kMillisecond)->MinTime(0.3);
}
BENCHMARK(BM_RetargetSynthetic)->Apply(RatiosAndSolvers);
BENCHMARK(BM_RetargetSoldierToXbot)->Apply(RatiosAndSolvers);
BENCHMARK(BM_RetargetCesiumManToRiggedFigure)->Apply(RatiosAndSolvers);

void BM_RetargetSkeletonOnly(benchmark::State& state) {
  Skeleton source;
  Motion motion;
  Status status = ReadMotionFile(GltfFile("../bvh/16_15.bvh"), MotionFileOptions(), &source, &motion);
  GltfCharacter xbot;
  if (status.ok()) status = ReadGltfCharacter(GltfFile("Xbot.glb"), GltfReadOptions(), &xbot);
  if (!status.ok()) return state.SkipWithError(status.message().c_str());
  motion.frames.resize(std::min(motion.num_frames(), 120));
  RetargetCharacter source_view;
  source_view.skeleton = &source;
  const RetargetCharacter target_view = {&xbot.skeleton, &xbot.mesh, xbot.bind_pose, xbot.rest_pose};
  CharacterRetargetOptions options;
  options.plant_feet = state.range(0) != 0;
  options.clip.solve.limb_direction_weight = state.range(1) != 0 ? 2.0 : 0.0;  // retarget's default: 2.
  CharacterRetargetResult result;
  for (auto _ : state) {
    status = RetargetMotionOntoCharacter(source_view, motion, target_view, options, &result);
    if (!status.ok()) return state.SkipWithError(status.message().c_str());
  }
  state.SetLabel(std::string(options.plant_feet ? "16_15 onto Xbot, feet planted" : "16_15 onto Xbot, no foot plants") +
                 (state.range(1) != 0 ? ", limb directions (weight 2)" : ""));
  state.counters["solve_ms_per_frame"] = 1e3 * result.clip.solve_seconds / motion.num_frames();
  state.counters["setup_ms"] = 1e3 * result.setup_seconds;
  state.counters["vertex_error"] = result.clip.mean_position_error;
  state.counters["limb_mean_deg"] = result.quality.limb_mean_deg;
  state.counters["effector_error"] = result.clip.mean_effector_error;
  state.counters["skating_cm_s_source"] = result.source_plant_skating_cm_s;
  state.counters["skating_cm_s_result"] = result.result_plant_skating_cm_s;
}
BENCHMARK(BM_RetargetSkeletonOnly)->Args({0, 0})->Args({1, 0})->Args({1, 1})->ArgNames({"plant", "limbs"})->Unit(benchmark::kMillisecond)->MinTime(0.3);

// Thesis Table 3: stage shares of one DLS iteration at 128:1.
void BM_RetargetStages(benchmark::State& state) {
  const Case& c = GetCase(static_cast<int>(state.range(0)), 128);
  if (!c.status.ok()) return state.SkipWithError(c.status.message().c_str());
  RetargetSolveOptions options;
  options.iterations = 5;
  options.time_stages = true;
  RetargetFrameSolver solver(c.target.skeleton, c.target.mesh, c.setup, c.goals.sigma, options);
  Pose pose = StartPose(c);
  int f = 0;
  for (auto _ : state) {
    (void)solver.Solve(c.goals.positions[f], c.goals.normals[f], &pose, nullptr);
    if (++f == kLoopFrames) f = 0;
  }
  const char* kCaseNames[] = {"synthetic", "Soldier onto Xbot", "CesiumMan onto RiggedFigure"};
  state.SetLabel(kCaseNames[state.range(0)]);
  const RetargetStageTimes& t = solver.stage_times();
  const double total = t.total();
  state.counters["fk_%"] = 100.0 * t.fk / total;
  state.counters["skinning_%"] = 100.0 * t.skinning / total;
  state.counters["jacobian_%"] = 100.0 * t.jacobian / total;
  state.counters["solve_%"] = 100.0 * t.solve / total;
  state.counters["update_%"] = 100.0 * t.update / total;
  state.counters["us_per_iteration"] = 1e6 * total / t.iterations;
}
BENCHMARK(BM_RetargetStages)->Arg(0)->Arg(1)->Arg(2)->ArgName("case")->Unit(benchmark::kMillisecond)->MinTime(0.3);

}  // namespace
}  // namespace mocapsolve
