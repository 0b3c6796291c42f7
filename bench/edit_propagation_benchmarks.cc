// Edit propagation benchmarks (issue 6, the "magic wand" falloff): building the pose-space
// Green's function (Laplacian eigenpairs) for a clip, and re-propagating a new edit (one row
// of G plus its weights) once it is built.
//   build/bin/mocapsolve_bench --benchmark_filter=Green
// Clips: CMU 16_15 (a 471-frame walk) looped to N frames with each loop's joint rotations
// perturbed by seeded noise (0.02 rad), so the cycles are similar but not identical; without
// the data file the procedural demo walk (kinematics/demo_character.h) with the same noise.
// Targets: build <= 1 s at 10,000 frames (sparse kNN kernel, 10 eigenpairs); a new edit's
// row + weights <= 10 ms at 10,000 frames.
#include <cstdlib>
#include <map>
#include <random>
#include <string>

#include <benchmark/benchmark.h>

#include "io/motion_file.h"
#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"
#include "problems/edit_propagation/falloff.h"
#include "problems/edit_propagation/isomap_distance.h"
#include "problems/edit_propagation/pose_features.h"
#include "problems/edit_propagation/pose_kernel.h"

namespace mocapsolve {
namespace {

std::string WalkFile() {
  const char* env = std::getenv("MOCAPSOLVE_DATA");
  const std::string root = env != nullptr && *env ? env : MOCAPSOLVE_SOURCE_DIR "/../shared/data";
  return root + "/bvh/16_15.bvh";
}

// Pose vectors of an N-frame looped, perturbed walk; cached per N.
const Eigen::MatrixXd& LongWalkFeatures(int num_frames) {
  static std::map<int, Eigen::MatrixXd> cache;
  auto it = cache.find(num_frames);
  if (it != cache.end()) return it->second;
  Skeleton skeleton;
  Motion source;
  if (!ReadMotionFile(WalkFile(), MotionFileOptions(), &skeleton, &source).ok()) {
    skeleton = MakeDemoSkeleton();
    source = MakeDemoWalk(skeleton, 240, 120.0);
  }
  std::mt19937 rng(6);
  std::normal_distribution<double> noise(0.0, 0.02);
  Motion motion;
  motion.frame_rate = source.frame_rate;
  while (motion.num_frames() < num_frames) {
    std::vector<Eigen::Vector3d> offsets(skeleton.num_joints());
    for (auto& o : offsets) o = Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    for (const Pose& pose : source.frames) {
      if (motion.num_frames() == num_frames) break;
      Pose p = pose;
      for (int j = 0; j < skeleton.num_joints(); ++j) {
        p.rotations[j] = (p.rotations[j] * ExpMap(offsets[j] + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)) * 0.1)).normalized();
      }
      motion.frames.push_back(p);
    }
  }
  Eigen::MatrixXd features;
  if (!PoseFeatures(skeleton, motion, PoseFeatureOptions(), &features).ok()) features.resize(0, 0);
  return cache.emplace(num_frames, std::move(features)).first->second;
}

void BuildGreen(benchmark::State& state, KernelMode mode) {
  const Eigen::MatrixXd& features = LongWalkFeatures(static_cast<int>(state.range(0)));
  if (features.rows() == 0) return state.SkipWithError("could not make the clip");
  FalloffOptions options;
  options.kernel = mode;
  GreenFunction green;
  for (auto _ : state) {
    Status status = green.Build(features, options);
    if (!status.ok()) return state.SkipWithError(status.message().c_str());
    benchmark::DoNotOptimize(green.eigenpairs().eigenvalues.data());
  }
  state.counters["frames"] = static_cast<double>(features.rows());
  state.counters["eigenpairs"] = green.eigenpairs_used();
  state.counters["lambda_1"] = green.eigenpairs().eigenvalues.size() > 1 ? green.eigenpairs().eigenvalues[1] : 0.0;
}

void BM_GreenBuildDense(benchmark::State& state) { BuildGreen(state, KernelMode::kDense); }
BENCHMARK(BM_GreenBuildDense)->Arg(1000)->ArgName("frames")->Unit(benchmark::kMillisecond);

void BM_GreenBuildSparse(benchmark::State& state) { BuildGreen(state, KernelMode::kSparse); }
BENCHMARK(BM_GreenBuildSparse)->Arg(1000)->Arg(10000)->ArgName("frames")->Unit(benchmark::kMillisecond);

// A new edit once G is built: row + normalization over the whole clip.
void BM_GreenRepropagate(benchmark::State& state) {
  const Eigen::MatrixXd& features = LongWalkFeatures(static_cast<int>(state.range(0)));
  if (features.rows() == 0) return state.SkipWithError("could not make the clip");
  GreenFunction green;
  Status status = green.Build(features, FalloffOptions());
  if (!status.ok()) return state.SkipWithError(status.message().c_str());
  const int n = green.num_frames();
  Falloff falloff;
  int frame = 0;
  for (auto _ : state) {
    green.Weights(frame, 0, n, &falloff);
    benchmark::DoNotOptimize(falloff.weight.data());
    frame = (frame + 997) % n;
  }
  state.counters["frames"] = n;
}
BENCHMARK(BM_GreenRepropagate)->Arg(10000)->ArgName("frames")->Unit(benchmark::kMicrosecond);

// The approximate kNN graph alone (the first part of a sparse build).
void BM_PoseKnnGraph(benchmark::State& state) {
  const Eigen::MatrixXd& features = LongWalkFeatures(static_cast<int>(state.range(0)));
  if (features.rows() == 0) return state.SkipWithError("could not make the clip");
  for (auto _ : state) {
    auto graph = PoseNeighbourGraph(features, FalloffOptions().knn);
    benchmark::DoNotOptimize(graph.data());
  }
}
BENCHMARK(BM_PoseKnnGraph)->Arg(10000)->ArgName("frames")->Unit(benchmark::kMillisecond);

void BM_IsomapDistance(benchmark::State& state) {
  const Eigen::MatrixXd& features = LongWalkFeatures(static_cast<int>(state.range(0)));
  if (features.rows() == 0) return state.SkipWithError("could not make the clip");
  const auto graph = PoseNeighbourGraph(features, FalloffOptions().isomap_knn);
  int frame = 0;
  for (auto _ : state) {
    Eigen::VectorXd d = GeodesicDistances(graph, frame);
    benchmark::DoNotOptimize(d.data());
    frame = (frame + 997) % static_cast<int>(features.rows());
  }
}
BENCHMARK(BM_IsomapDistance)->Arg(10000)->ArgName("frames")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mocapsolve
