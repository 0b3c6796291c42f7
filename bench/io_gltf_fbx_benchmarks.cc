// Load-time benchmarks of the glTF and FBX readers, and write-time benchmarks of the
// delivered character files (Google Benchmark).
//   build/bin/mocapsolve_bench --benchmark_filter='Gltf|Fbx|Deliver'
// Data from MOCAPSOLVE_DATA (default ../shared/data); without it these cases report an
// error. Figures: Xbot.glb (1.8 MB, 65 joints, 28374 vertices) parse + character in
// ms; one animation sampled; an FBX clip through assimp; Xbot with a 1854-frame take
// (CMU 02_05's length at 120 fps) written as GLB and as FBX, whole or animation only,
// with the file's bytes as a counter.
#include <cstdlib>
#include <string>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>

#include "io/atomic_file.h"
#include "io/fbx_reader.h"
#include "io/fbx_writer.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"

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

// Writing a delivered take: Xbot and 1854 frames at 120 fps (every joint turning a few
// degrees, the root walking), as pipeline writes <character>.glb or .fbx (to a file in
// /tmp, atomically). state.range(0): 0 = GLB, 1 = FBX; range(1): 1 = animation only.
void BM_DeliverTake(benchmark::State& state) {
  GltfDocument document;
  GltfCharacter character;
  Status status = GltfDocument::Read(DataPath("gltf/Xbot.glb"), &document);
  if (status.ok()) status = ReadGltfCharacter(document, {}, &character);
  if (!status.ok()) return state.SkipWithError(status.message().c_str());
  Motion motion;
  motion.frame_rate = 120.0;
  for (int f = 0; f < 1854; ++f) {
    Pose pose = character.rest_pose;
    for (size_t j = 0; j < pose.rotations.size(); ++j) {
      const double angle = 0.1 * std::sin(0.05 * f + 0.3 * j);
      pose.rotations[j] = pose.rotations[j] * Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()));
    }
    pose.translations[0] += Eigen::Vector3d(0.0, 0.0, 0.01 * f);
    motion.frames.push_back(pose);
  }
  const bool fbx = state.range(0) == 1, animation_only = state.range(1) == 1;
  const std::string path = std::string("/tmp/mocapsolve_bench_deliver") + (fbx ? ".fbx" : ".glb");
  for (auto _ : state) {
    if (fbx) {
      status = WriteFbxCharacter(path, character, motion, "take", animation_only);
    } else {
      GltfWriteOptions options;
      options.animation_only = animation_only;
      status = WriteGltfWithAnimation(document, character, motion, "take", path, options);
    }
    if (!status.ok()) return state.SkipWithError(status.message().c_str());
  }
  std::string bytes;
  if (ReadFileToString(path, &bytes).ok()) state.counters["bytes"] = static_cast<double>(bytes.size());
  std::remove(path.c_str());
}
BENCHMARK(BM_DeliverTake)->ArgsProduct({{0, 1}, {0, 1}})->ArgNames({"fbx", "animation_only"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mocapsolve
