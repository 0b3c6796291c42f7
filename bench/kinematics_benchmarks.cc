// Micro benchmarks of the kinematic core and the BVH parser (Google Benchmark).
//   build/bin/mocapsolve_bench [--benchmark_format=json]
// Real clips come from MOCAPSOLVE_DATA (default ../shared/data); without them the
// data-based cases report an error and the others still run.
// Targets (issue 2): FK <= 0.5 us per frame on the CMU 31-joint skeleton; BVH parse
// >= 100 MB/s.
#include <cstdlib>
#include <random>
#include <string>

#include <benchmark/benchmark.h>

#include "bench/bench_data.h"
#include "io/atomic_file.h"
#include "io/bvh_reader.h"
#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/kinematic_jacobians.h"
#include "kinematics/skinning.h"

namespace mocapsolve {
namespace {

// The CMU 31-joint clip, loaded once.
struct Clip {
  Skeleton skeleton;
  Motion motion;
  std::string text;
  Status status = Status::Error("not loaded");
};

const Clip& Cmu0101() {
  static const Clip clip = [] {
    Clip c;
    c.status = ReadFileToString(DataFile("bvh/01_01.bvh"), &c.text);
    if (c.status.ok()) c.status = ParseBvh(c.text, "01_01.bvh", &c.skeleton, &c.motion);
    return c;
  }();
  return clip;
}

void BM_ForwardKinematicsPerFrame(benchmark::State& state) {
  const Clip& clip = Cmu0101();
  if (!clip.status.ok()) return state.SkipWithError(clip.status.message().c_str());
  FkData data(clip.skeleton);
  size_t f = 0;
  for (auto _ : state) {
    ForwardKinematics(clip.skeleton, clip.motion.frames[f], &data);
    benchmark::DoNotOptimize(data.world_positions.data());
    benchmark::ClobberMemory();
    if (++f == clip.motion.frames.size()) f = 0;
  }
  state.counters["joints"] = clip.skeleton.num_joints();
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ForwardKinematicsPerFrame);

void BM_BvhParse(benchmark::State& state) {
  const Clip& clip = Cmu0101();
  if (!clip.status.ok()) return state.SkipWithError(clip.status.message().c_str());
  for (auto _ : state) {
    Skeleton skeleton;
    Motion motion;
    Status status = ParseBvh(clip.text, "01_01.bvh", &skeleton, &motion);
    benchmark::DoNotOptimize(motion.frames.data());
    if (!status.ok()) state.SkipWithError(status.message().c_str());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * clip.text.size());
}
BENCHMARK(BM_BvhParse)->Unit(benchmark::kMillisecond);

// A skinned mesh on the demo character: 4 influences per vertex on nearby joints.
struct Rig {
  Skeleton skeleton = MakeDemoSkeleton();
  SkinnedMesh mesh;
  Pose pose;
  Rig() {
    std::mt19937 rng(3);
    std::normal_distribution<double> normal;
    FkData bind(skeleton);
    ForwardKinematics(skeleton, RestPose(skeleton), &bind);
    SkinnedMeshSpec spec;
    const int nv = 4000;
    spec.rest_positions.resize(3, nv);
    spec.rest_normals.resize(3, nv);
    for (int i = 0; i < nv; ++i) {
      const int j = i % skeleton.num_joints();
      spec.rest_positions.col(i) = bind.world_positions[j] + 3.0 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
      spec.rest_normals.col(i) = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      const int p = std::max(0, skeleton.parent(j));
      spec.influences.push_back({{j, 0.5}, {p, 0.25}, {std::max(0, skeleton.parent(p)), 0.15}, {0, 0.1}});
    }
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      Eigen::Isometry3d world_from_joint = Eigen::Isometry3d::Identity();
      world_from_joint.linear() = bind.world_rotations[j].toRotationMatrix();
      world_from_joint.translation() = bind.world_positions[j];
      spec.joint_from_bind.push_back(world_from_joint.inverse());
    }
    (void)SkinnedMesh::Create(skeleton, spec, &mesh);
    pose = MakeDemoWalk(skeleton, 10, 30.0).frames[7];
  }
};

void BM_LbsPerVertex(benchmark::State& state) {
  static const Rig rig;
  FkData fk(rig.skeleton);
  ForwardKinematics(rig.skeleton, rig.pose, &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(rig.mesh, fk, &transforms);
  Eigen::Matrix3Xd positions, normals;
  for (auto _ : state) {
    SkinMesh(rig.mesh, transforms, &positions, &normals);
    benchmark::DoNotOptimize(positions.data());
  }
  state.SetItemsProcessed(state.iterations() * rig.mesh.num_vertices());
  // Per vertex: the reported time divided by "vertices" (items_per_second inverted).
  state.counters["vertices"] = rig.mesh.num_vertices();
}
BENCHMARK(BM_LbsPerVertex)->Unit(benchmark::kMicrosecond);

void BM_SkinnedPositionJacobianFill(benchmark::State& state) {
  static const Rig rig;
  FkData fk(rig.skeleton);
  ForwardKinematics(rig.skeleton, rig.pose, &fk);
  std::vector<Eigen::Isometry3d> transforms;
  ComputeSkinningTransforms(rig.mesh, fk, &transforms);
  PoseJacobian jacobian(3, PoseTangentSize(rig.skeleton));
  int v = 0;
  for (auto _ : state) {
    SkinnedPositionJacobian(rig.skeleton, rig.mesh, fk, transforms, v, &jacobian);
    benchmark::DoNotOptimize(jacobian.data());
    if (++v == rig.mesh.num_vertices()) v = 0;
  }
}
BENCHMARK(BM_SkinnedPositionJacobianFill);

void BM_JointPositionJacobianFill(benchmark::State& state) {
  const Clip& clip = Cmu0101();
  if (!clip.status.ok()) return state.SkipWithError(clip.status.message().c_str());
  FkData fk(clip.skeleton);
  ForwardKinematics(clip.skeleton, clip.motion.frames[100], &fk);
  PoseJacobian jacobian(3, PoseTangentSize(clip.skeleton));
  for (auto _ : state) {
    // All joints of one frame: the dense Jacobian of a whole skeleton's positions.
    for (int j = 0; j < clip.skeleton.num_joints(); ++j) {
      JointPositionJacobian(clip.skeleton, fk, j, &jacobian);
      benchmark::DoNotOptimize(jacobian.data());
    }
  }
}
BENCHMARK(BM_JointPositionJacobianFill);

}  // namespace
}  // namespace mocapsolve

BENCHMARK_MAIN();
