// Regression: FK of a real clip against pinned golden positions (tests/data/golden).
// Regenerate only deliberately: build/bin/fk_golden_test --update_golden, then review
// the diff.
#include <gtest/gtest.h>

#include "io/amc_reader.h"
#include "io/asf_reader.h"
#include "io/bvh_reader.h"
#include "kinematics/forward_kinematics.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

std::vector<std::vector<double>> SampledPositions(const Skeleton& skeleton, const Motion& motion,
                                                  int stride) {
  std::vector<std::vector<double>> rows;
  FkData data(skeleton);
  for (int f = 0; f < motion.num_frames(); f += stride) {
    ForwardKinematics(skeleton, motion.frames[f], &data);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      const Eigen::Vector3d& p = data.world_positions[j];
      rows.push_back({static_cast<double>(f), static_cast<double>(j), p.x(), p.y(), p.z()});
    }
  }
  return rows;
}

// The values are printed with 10 significant digits (~1e-8 cm at 100 cm); FK itself is
// deterministic to round-off, so 1e-6 file units leaves room only for compiler changes.
constexpr double kGoldenTolerance = 1e-6;

TEST(FkGolden, Cmu1615Bvh) {
  MOCAPSOLVE_DATA_FILE(path, "bvh/16_15.bvh");
  Skeleton skeleton;
  Motion motion;
  const Status status = ReadBvh(path, &skeleton, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  testing::ExpectMatchesGolden("fk_16_15_bvh", {"frame", "joint", "x", "y", "z"},
                               SampledPositions(skeleton, motion, 47), kGoldenTolerance);
}

TEST(FkGolden, Cmu0101Bvh) {
  MOCAPSOLVE_DATA_FILE(path, "bvh/01_01.bvh");
  Skeleton skeleton;
  Motion motion;
  const Status status = ReadBvh(path, &skeleton, &motion);
  ASSERT_TRUE(status.ok()) << status.message();
  testing::ExpectMatchesGolden("fk_01_01_bvh", {"frame", "joint", "x", "y", "z"},
                               SampledPositions(skeleton, motion, 250), kGoldenTolerance);
}

}  // namespace
}  // namespace mocapsolve
