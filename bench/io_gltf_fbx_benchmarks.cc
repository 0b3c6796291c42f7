// Load-time benchmarks of the glTF and FBX readers (Google Benchmark).
//   build/bin/mocapsolve_bench --benchmark_filter='Gltf|Fbx'
// Data from MOCAPSOLVE_DATA (default ../shared/data); without it these cases report an
// error. Figures: Xbot.glb (1.8 MB, 65 joints, 28374 vertices) parse + character in
// ms; one animation sampled; an FBX clip through assimp.
#include <cstdlib>
#include <string>

#include <benchmark/benchmark.h>

#include "io/atomic_file.h"
#include "io/fbx_reader.h"
#include "io/gltf_reader.h"

namespace mocapsolve {
namespace {

std::string DataPath(const std::string& relative) {
  const char* env = std::getenv("MOCAPSOLVE_DATA");
  const std::string root = env != nullptr && *env ? env : MOCAPSOLVE_SOURCE_DIR "/../shared/data";
  return root + "/" + relative;
}

// Whole load from disk: read, parse (tinygltf), skeleton + skinned mesh.
void BM_GltfLoadCharacter(benchmark::State& state, const char* file) {
  const std::string path = DataPath(std::string("gltf/") + file);
  GltfCharacter character;
  for (auto _ : state) {
    const Status status = ReadGltfCharacter(path, {}, &character);
    if (!status.ok()) return state.SkipWithError(status.message().c_str());
    benchmark::DoNotOptimize(character.mesh.rest_positions().data());
  }
  state.counters["joints"] = character.skeleton.num_joints();
  state.counters["vertices"] = character.mesh.num_vertices();
}
BENCHMARK_CAPTURE(BM_GltfLoadCharacter, Xbot, "Xbot.glb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GltfLoadCharacter, CesiumMan, "CesiumMan.glb")->Unit(benchmark::kMillisecond);

// Sampling one clip of a loaded document (Soldier's Walk, 24 fps).
void BM_GltfSampleAnimation(benchmark::State& state) {
  GltfDocument document;
  GltfCharacter character;
  Status status = GltfDocument::Read(DataPath("gltf/Soldier.glb"), &document);
  if (status.ok()) status = ReadGltfCharacter(document, {}, &character);
  if (!status.ok()) return state.SkipWithError(status.message().c_str());
  GltfAnimationOptions options;
  options.animation = "Walk";
  Motion motion;
  for (auto _ : state) {
    status = ReadGltfAnimation(document, character, options, &motion);
    if (!status.ok()) return state.SkipWithError(status.message().c_str());
    benchmark::DoNotOptimize(motion.frames.data());
  }
  state.counters["frames"] = motion.num_frames();
}
BENCHMARK(BM_GltfSampleAnimation)->Unit(benchmark::kMicrosecond);

void BM_FbxLoad(benchmark::State& state) {
  const std::string path = DataPath("fbx/09_11_cmu.fbx");
  Skeleton skeleton;
  Motion motion;
  for (auto _ : state) {
    const Status status = ReadFbx(path, {}, &skeleton, &motion);
    if (!status.ok()) return state.SkipWithError(status.message().c_str());
    benchmark::DoNotOptimize(motion.frames.data());
  }
  state.counters["frames"] = motion.num_frames();
}
BENCHMARK(BM_FbxLoad)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mocapsolve
