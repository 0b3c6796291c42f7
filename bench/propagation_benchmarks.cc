// Edit propagation, edit side (issue 6): the harmonic falloff solve (one field, Ceres
// SPARSE_NORMAL_CHOLESKY on Eigen's sparse LDLT) at 1k and 10k frames of the demo walk,
// the kNN pose graph it runs on, eq. 5 applied to a whole clip, and the foot-contact
// re-solve on CMU 16_15.
//   build/bin/mocapsolve_bench --benchmark_filter=Harmonic
#include <cstdlib>
#include <map>
#include <string>

#include <benchmark/benchmark.h>

#include "io/motion_file.h"
#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"
#include "problems/edit_propagation/foot_contacts.h"
#include "problems/edit_propagation/harmonic_falloff.h"
#include "problems/edit_propagation/pose_edit.h"
#include "problems/edit_propagation/spline_falloff.h"

namespace mocapsolve {
namespace {

struct PropagationFixture {
  Skeleton skeleton;
  Motion motion;
  Eigen::MatrixXd features;  // #frames x 3 #J: concatenated joint log rotations.
  std::vector<WeightedEdge> edges;
};

const PropagationFixture& Fixture(int frames) {
  static std::map<int, PropagationFixture> cache;
  auto it = cache.find(frames);
  if (it != cache.end()) return it->second;
  PropagationFixture& f = cache[frames];
  f.skeleton = MakeDemoSkeleton();
  f.motion = MakeDemoWalk(f.skeleton, frames, 120.0);
  const int joints = f.skeleton.num_joints();
  f.features.resize(frames, 3 * joints);
  for (int i = 0; i < frames; ++i) {
    for (int j = 0; j < joints; ++j) f.features.block<1, 3>(i, 3 * j) = LogMap(f.motion.frames[i].rotations[j]).transpose();
  }
  f.edges = PoseGraphEdges(f.features, 10, 0.2);
  return f;
}

// range(1): 0 = Eigen's sparse LDLT (default), 1 = SuiteSparse CHOLMOD.
void BM_HarmonicFalloffSolve(benchmark::State& state) {
  const int frames = static_cast<int>(state.range(0));
  const PropagationFixture& f = Fixture(frames);
  HarmonicOptions options;
  options.sparse_library = state.range(1) == 0 ? ceres::EIGEN_SPARSE : ceres::SUITE_SPARSE;
  std::string error;
  if (!options.IsValid(&error)) {
    state.SkipWithError(error.c_str());
    return;
  }
  std::vector<Eigen::VectorXd> fields;
  HarmonicReport report;
  for (auto _ : state) {
    const Status status = HarmonicFalloffs(frames, f.edges, {frames / 2}, {0, frames - 1},
                                           options, &fields, &report);
    if (!status.ok()) state.SkipWithError(status.message().c_str());
    benchmark::DoNotOptimize(fields.data());
  }
  state.counters["edges"] = static_cast<double>(f.edges.size());
  state.counters["iterations"] = report.iterations;
  state.counters["max_gradient"] = report.max_gradient;
}
BENCHMARK(BM_HarmonicFalloffSolve)->ArgsProduct({{1000, 10000}, {0, 1}})->ArgNames({"frames", "cholmod"})->Unit(benchmark::kMillisecond);

void BM_PoseGraphEdges(benchmark::State& state) {
  const PropagationFixture& f = Fixture(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    std::vector<WeightedEdge> edges = PoseGraphEdges(f.features, 10, 0.2);
    benchmark::DoNotOptimize(edges.data());
  }
}
BENCHMARK(BM_PoseGraphEdges)->Arg(1000)->Arg(10000)->ArgName("frames")->Unit(benchmark::kMillisecond);

void BM_PropagateEdits(benchmark::State& state) {
  const int frames = static_cast<int>(state.range(0));
  const PropagationFixture& f = Fixture(frames);
  PoseOffsets offsets;
  offsets.frame = frames / 2;
  for (int j = 0; j < f.skeleton.num_joints(); ++j) offsets.rotation_offsets.emplace_back(j, Eigen::Vector3d(0.1, 0.2, -0.1));
  PoseEdit edit;
  if (!MakeEdit(f.motion, offsets, &edit).ok()) state.SkipWithError("MakeEdit");
  const Eigen::VectorXd weights = SplineFalloff(frames, frames / 2, frames / 4.0);
  Motion out;
  for (auto _ : state) {
    const Status status = PropagateEdits(f.skeleton, f.motion, {edit}, {weights}, &out);
    if (!status.ok()) state.SkipWithError(status.message().c_str());
    benchmark::DoNotOptimize(out.frames.data());
  }
}
BENCHMARK(BM_PropagateEdits)->Arg(1000)->Arg(10000)->ArgName("frames")->Unit(benchmark::kMillisecond);

// KeepContacts on CMU 16_15 (471 frames, cm) after a hips edit spread over +-80 frames:
// the per-frame re-solves of the planted frames plus the blending.
void BM_KeepContacts16_15(benchmark::State& state) {
  const char* env = std::getenv("MOCAPSOLVE_DATA");
  const std::string root = env != nullptr && *env ? env : MOCAPSOLVE_SOURCE_DIR "/../shared/data";
  Skeleton skeleton;
  Motion motion;
  if (!ReadMotionFile(root + "/bvh/16_15.bvh", MotionFileOptions(), &skeleton, &motion).ok()) {
    state.SkipWithError("bvh/16_15.bvh not found (set MOCAPSOLVE_DATA)");
    return;
  }
  FootContactOptions detect;
  detect.height_threshold = 5.0;  // cm
  detect.speed_threshold = 20.0;  // cm/s
  FootContacts contacts;
  PoseOffsets offsets;
  offsets.frame = 200;
  offsets.root_translation_offset = Eigen::Vector3d(0.0, -6.0, 0.0);
  PoseEdit edit;
  Motion propagated;
  if (!DetectFootContacts(skeleton, motion, detect, &contacts).ok() || !MakeEdit(motion, offsets, &edit).ok() ||
      !PropagateEdits(skeleton, motion, {edit}, {SplineFalloff(motion.num_frames(), 200, 80.0)}, &propagated).ok()) {
    state.SkipWithError("setup failed");
    return;
  }
  ContactSolveReport report;
  for (auto _ : state) {
    Motion kept = propagated;
    const Status status = KeepContacts(skeleton, contacts, ContactSolveOptions(), &kept, &report);
    if (!status.ok()) state.SkipWithError(status.message().c_str());
    benchmark::DoNotOptimize(kept.frames.data());
  }
  state.counters["contact_frames"] = report.frames_solved;
  state.counters["drift_cm_before"] = report.max_drift_before;
  state.counters["drift_cm_after"] = report.max_drift_after;
}
BENCHMARK(BM_KeepContacts16_15)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mocapsolve
