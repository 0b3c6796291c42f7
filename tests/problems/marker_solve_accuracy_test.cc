// Issue 3 accuracy on real clips: noise-free markers synthesized from CMU 16_15 and
// 01_01 (3 markers per solved bone) must be solved back to within 1 mm in joint position
// and 0.5 degrees in the rotation of every markered bone, by both solvers.
#include <gtest/gtest.h>

#include "io/bvh_reader.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/sequence_solver.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

struct Case {
  const char* file;
  double mm_per_unit;  // 16_15 is in cm; 01_01 in CMU ASF units (1/0.45 inch).
  int stride;          // Solve every stride-th frame (warm-started across the gap).
};

void ExpectRecovered(const Case& c, SolverKind solver_kind) {
  MOCAPSOLVE_DATA_FILE(path, c.file);
  Skeleton skeleton;
  Motion clip;
  Status status = ReadBvh(path, &skeleton, &clip);
  ASSERT_TRUE(status.ok()) << status.message();
  Motion truth;
  truth.frame_rate = clip.frame_rate / c.stride;
  for (int f = 0; f < clip.num_frames(); f += c.stride) truth.frames.push_back(clip.frames[f]);
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, 7);
  std::vector<bool> markered(skeleton.num_joints(), false);
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (const auto& a : markers.marker(m).attachments) markered[a.joint] = true;
  }
  std::vector<std::vector<Eigen::Vector3d>> observed;
  FkData fk(skeleton);
  for (const Pose& pose : truth.frames) {
    ForwardKinematics(skeleton, pose, &fk);
    observed.emplace_back();
    for (int m = 0; m < markers.num_markers(); ++m) observed.back().push_back(markers.Position(m, fk));
  }
  MarkerSolveOptions options;
  options.solver = solver_kind;
  options.ceres = DefaultFrameCeresOptions();
  Motion solved;
  SequenceSolveReport report;
  Pose initial = RestPose(skeleton);
  status = SolveSequence(skeleton, markers, observed, options, initial, &solved, &report);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(report.unsolved_frames, 0);

  const double one_mm = 1.0 / c.mm_per_unit;
  FkData a(skeleton), b(skeleton);
  double worst_position = 0.0, worst_angle = 0.0;
  for (int f = 0; f < truth.num_frames(); ++f) {
    ForwardKinematics(skeleton, solved.frames[f], &a);
    ForwardKinematics(skeleton, truth.frames[f], &b);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      worst_position = std::max(worst_position, (a.world_positions[j] - b.world_positions[j]).norm());
      if (markered[j]) {
        worst_angle = std::max(worst_angle, AngularDistance(a.world_rotations[j], b.world_rotations[j]));
      }
    }
  }
  EXPECT_LT(worst_position, one_mm) << "worst joint position error " << worst_position * c.mm_per_unit << " mm";
  EXPECT_LT(RadToDeg(worst_angle), 0.5) << "worst markered-bone rotation error " << RadToDeg(worst_angle) << " deg";
  std::printf("%s %s: %d frames, %.1f iterations/frame, worst joint error %.3g mm, worst bone rotation %.3g deg, %.0f frames/s\n",
              c.file, solver_kind == SolverKind::kCeres ? "ceres" : "dls", truth.num_frames(), double(report.total_iterations) / truth.num_frames(),
              worst_position * c.mm_per_unit, RadToDeg(worst_angle), truth.num_frames() / report.solve_seconds);
}

constexpr double kCmuMmPerUnit = 25.4 / 0.45;

TEST(MarkerSolveAccuracy, Cmu1615Ceres) { ExpectRecovered({"bvh/16_15.bvh", 10.0, 1}, SolverKind::kCeres); }
TEST(MarkerSolveAccuracy, Cmu1615Dls) { ExpectRecovered({"bvh/16_15.bvh", 10.0, 1}, SolverKind::kDls); }
TEST(MarkerSolveAccuracy, Cmu0101Ceres) { ExpectRecovered({"bvh/01_01.bvh", kCmuMmPerUnit, 4}, SolverKind::kCeres); }
TEST(MarkerSolveAccuracy, Cmu0101Dls) { ExpectRecovered({"bvh/01_01.bvh", kCmuMmPerUnit, 4}, SolverKind::kDls); }

}  // namespace
}  // namespace mocapsolve
