// Joint map benchmarks (problems/retarget/joint_map.h, humanoid_roles.h), Google Benchmark:
//   build/bin/mocapsolve_bench --benchmark_filter=JointMap
// One iteration builds the map as a retarget does: both skeletons' standing positions
// (FK of the bind pose and of the other pose), the name passes, the humanoid roles of both
// sides by structure, the merge. Target: < 50 ms. Pairs (MOCAPSOLVE_DATA, default
// ../shared/data; skipped with an error without it): CMU 01_01 (BVH, 31 joints) onto Xbot
// (65 joints) with its joints renamed to random names (so structure decides every role),
// and onto RobotExpressive (43 joints, floor root, IK feet).
#include <cstdlib>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_data.h"
#include "io/gltf_reader.h"
#include "io/motion_file.h"
#include "problems/retarget/joint_map.h"

namespace mocapsolve {
namespace {

void BM_JointMap(benchmark::State& state, const char* target_name, bool rename) {
  Skeleton source;
  Motion motion;
  GltfCharacter target;
  Status status = ReadMotionFile(DataFile("bvh/01_01.bvh"), MotionFileOptions(), &source, &motion);
  if (status.ok()) status = ReadGltfCharacter(DataFile(std::string("gltf/") + target_name + ".glb"), GltfReadOptions(), &target);
  if (!status.ok()) {
    state.SkipWithError(status.message().c_str());
    return;
  }
  Skeleton target_skeleton = target.skeleton;
  if (rename) {
    std::vector<JointSpec> specs;
    for (int j = 0; j < target.skeleton.num_joints(); ++j) {
      specs.push_back(target.skeleton.joint(j));
      specs.back().name = "j" + std::to_string(1000 + 7 * j);
    }
    if (!Skeleton::Create(specs, {}, target.skeleton.unit(), &target_skeleton).ok()) {
      state.SkipWithError("rename failed");
      return;
    }
  }
  JointMap map;
  for (auto _ : state) {
    status = BuildJointMap(StandingSkeleton(source, Pose(), nullptr, motion.frames[0]),
                           StandingSkeleton(target_skeleton, target.bind_pose, &target.mesh, target.rest_pose), {},
                           &map);
    benchmark::DoNotOptimize(map.num_mapped());
  }
  if (!status.ok()) state.SkipWithError(status.message().c_str());
  state.counters["mapped_joints"] = map.num_mapped();
  state.counters["roles"] = static_cast<double>(map.roles.size());
  state.counters["confidence"] = map.confidence;
}

BENCHMARK_CAPTURE(BM_JointMap, cmu_onto_xbot_renamed, "Xbot", true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_JointMap, cmu_onto_xbot, "Xbot", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_JointMap, cmu_onto_robot, "RobotExpressive", false)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mocapsolve
