// Regression: the whole repair pipeline (thesis ch. 3) on a damaged demo walk against pinned
// golden outputs (tests/data/golden): the intervals it detects and fills, and the repaired
// samples where the damage was. Regenerate only deliberately:
// build/bin/repair_golden_test --update_golden, then review the diff.
#include <gtest/gtest.h>

#include "problems/marker_repair/marker_repair.h"
#include "signal/marker_corruption.h"
#include "tests/problems/repair_test_support.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

double KindCode(const std::string& what) {
  const char* kinds[] = {"missing", "outlier", "joint difference", "polynomial", "reference", "reference only", "swap"};
  for (int k = 0; k < 7; ++k) {
    if (what == kinds[k]) return k;
  }
  return -1;
}

TEST(RepairGolden, DamagedDemoWalk) {
  const testing::DemoTake take = testing::MakeDemoTake(240, 120.0, 1);
  const Skeleton& skeleton = take.skeleton;
  const MarkerSet& markers = take.markers;
  MarkerTrajectories x = ObservationTrajectories(markers, take.clean);
  CorruptionOptions damage;  // The `corrupt` defaults, in cm.
  damage.seed = 1;
  damage.cluster_radius = 15.0;
  damage.fly_off_distance = 10.0;
  damage.swap_radius = 20.0;
  damage.noise_sigma = 0.5;
  CorruptionMask mask;
  CorruptMarkers(damage, &x, &mask);
  const auto corrupted = TrajectoryObservations(x);

  const RepairOptions options = testing::DemoRepairOptions(ReferenceKind::kTracker);  // `repair`'s defaults
  std::vector<std::vector<Eigen::Vector3d>> repaired;
  Motion motion;
  RepairReport report;
  const Status status = RepairMarkers(skeleton, markers, corrupted, options, &repaired, &motion, &report);
  ASSERT_TRUE(status.ok()) << status.message();

  std::vector<std::vector<double>> intervals;
  for (const RepairInterval& i : report.detected) intervals.push_back({0, double(i.marker), double(i.first), double(i.last), KindCode(i.what)});
  for (const RepairInterval& i : report.filled) intervals.push_back({1, double(i.marker), double(i.first), double(i.last), KindCode(i.what)});
  // Exact integers: any change in what is detected or filled shows.
  testing::ExpectMatchesGolden("repair_demo_intervals", {"filled", "marker", "first", "last", "kind"}, intervals, 0.0);

  std::vector<std::vector<double>> samples;
  for (size_t f = 0; f < repaired.size(); f += 3) {
    for (int m = 0; m < markers.num_markers(); ++m) {
      if (mask[f][m] == 0) continue;
      const Eigen::Vector3d& p = repaired[f][m];
      samples.push_back({double(f), double(m), p.x(), p.y(), p.z()});
    }
  }
  // Iterative solves end at a relative cost change of 1e-6: 1e-4 cm (a micron) leaves room
  // for compilers and libraries, and none for a change of method.
  testing::ExpectMatchesGolden("repair_demo_samples", {"frame", "marker", "x", "y", "z"}, samples, 1e-4);
}

}  // namespace
}  // namespace mocapsolve
