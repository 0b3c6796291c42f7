// Per-take offset refinement (problems/marker_solve/offset_refinement.h): on the true motion,
// a marker moved on its bone by a known shift is refined by n / (n + n0) of it; a marker with
// no sample keeps its calibrated offset bit for bit; max_shift bounds the move.
#include "problems/marker_solve/offset_refinement.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/problems/repair_test_support.h"

namespace mocapsolve {
namespace {

// The take with marker `moved` re-stuck `shift` (its joint's frame, cm) away.
testing::DemoTake MovedTake(int moved, const Eigen::Vector3d& shift) {
  testing::DemoTake take = testing::MakeDemoTake(20, 30.0, 5);
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < take.markers.num_markers(); ++m) specs.push_back(take.markers.marker(m));
  specs[moved].attachments[0].offset += shift;
  MarkerSet restuck;
  EXPECT_TRUE(MarkerSet::Create(take.skeleton, specs, &restuck).ok());
  FkData fk(take.skeleton);
  for (size_t f = 0; f < take.truth.frames.size(); ++f) {
    ForwardKinematics(take.skeleton, take.truth.frames[f], &fk);
    take.clean[f][moved] = restuck.Position(moved, fk);
  }
  return take;
}

TEST(OffsetRefinement, MovesAMarkerByItsShiftWeightedAgainstThePrior) {
  const int moved = 4;
  const Eigen::Vector3d shift(1.0, -2.0, 0.5);  // cm.
  const testing::DemoTake take = MovedTake(moved, shift);
  ASSERT_EQ(take.markers.marker(moved).attachments.size(), 1u);
  const Eigen::Vector3d z0 = take.markers.marker(moved).attachments[0].offset;
  for (double n0 : {0.0, 20.0, 60.0}) {
    OffsetRefinementOptions options;
    options.prior_frames = n0;
    MarkerSet refined;
    OffsetRefinementReport report;
    ASSERT_TRUE(RefineMarkerOffsets(take.skeleton, take.markers, take.clean, take.truth, options, &refined, &report).ok());
    const Eigen::Vector3d z = refined.marker(moved).attachments[0].offset;
    // 20 frames against n0 frames of prior: the mean local position is z0 + shift exactly.
    EXPECT_LT((z - (z0 + shift * 20.0 / (20.0 + n0))).norm(), 1e-9) << "n0 " << n0;
    EXPECT_EQ(report.refined, take.markers.num_markers());
    // The others did not move: their samples are their calibrated offsets (up to round-off).
    for (int m = 0; m < take.markers.num_markers(); ++m) {
      if (m != moved) {
        EXPECT_LT(report.shift[m], 1e-9);
      }
    }
  }
}

TEST(OffsetRefinement, AMarkerWithoutSamplesKeepsItsOffsetAndMaxShiftBounds) {
  const int moved = 4, unseen = 7;
  testing::DemoTake take = MovedTake(moved, Eigen::Vector3d(3.0, 0.0, 4.0));  // |shift| = 5 cm.
  // The unseen marker's samples all missing, the others' perturbed: it must not move at all.
  for (auto& frame : take.clean) frame[unseen] = Eigen::Vector3d::Constant(std::nan(""));
  OffsetRefinementOptions options;
  options.prior_frames = 0.0;
  options.max_shift = 2.0;
  MarkerSet refined;
  OffsetRefinementReport report;
  ASSERT_TRUE(RefineMarkerOffsets(take.skeleton, take.markers, take.clean, take.truth, options, &refined, &report).ok());
  EXPECT_EQ(refined.marker(unseen).attachments[0].offset, take.markers.marker(unseen).attachments[0].offset);
  EXPECT_EQ(report.shift[unseen], 0.0);
  EXPECT_EQ(report.refined, take.markers.num_markers() - 1);
  EXPECT_NEAR(report.shift[moved], 2.0, 1e-9);  // Bounded, radially.
  // Mismatched inputs are errors, not crashes.
  Motion short_motion = take.truth;
  short_motion.frames.pop_back();
  EXPECT_FALSE(RefineMarkerOffsets(take.skeleton, take.markers, take.clean, short_motion, options, &refined).ok());
}

}  // namespace
}  // namespace mocapsolve
