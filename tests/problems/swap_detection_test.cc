// Swap detection (issue 16 item 1) on crafted cases: the demo walk's markers with 1 mm of
// seeded noise, two markers of one bone exchanging labels (also from inside a gap, from
// the take's first frame and to its last), two pairs at once, and a ghost point beside a
// well tracked marker, which is no swap.
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "problems/marker_repair/marker_repair.h"
#include "tests/problems/repair_test_support.h"

namespace mocapsolve {
namespace {

using Observations = std::vector<std::vector<Eigen::Vector3d>>;

Observations Noisy(const Observations& clean, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  Observations out = clean;
  for (auto& frame : out) {
    for (Eigen::Vector3d& p : frame) p += Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  }
  return out;
}

struct Result {
  Observations repaired;
  RepairReport report;
  std::set<std::pair<int, int>> relabelled;  // (frame, label that received a sample).
};

Result Repair(const testing::DemoTake& take, const Observations& observed) {
  Result r;
  Motion motion;
  const RepairOptions options = testing::DemoRepairOptions(ReferenceKind::kTracker);
  const Status status = RepairMarkers(take.skeleton, take.markers, observed, options, &r.repaired, &motion, &r.report);
  EXPECT_TRUE(status.ok()) << status.message();
  for (const MarkerSwap& swap : r.report.swaps) {
    for (int f = swap.first; f <= swap.last; ++f) {
      for (const auto& [from, to] : swap.from_to) r.relabelled.insert({f, to});
    }
  }
  return r;
}

TEST(SwapDetection, SwapThatStartsInsideAGapIsRelabelled) {
  const testing::DemoTake take = testing::MakeDemoTake(160, 60.0, 5);
  const Observations truth = Noisy(take.clean, 0.1, 7);  // cm.
  const int a = take.markers.FindMarker("LeftLeg_0"), b = take.markers.FindMarker("LeftLeg_2");
  ASSERT_TRUE(a >= 0 && b >= 0);
  Observations observed = truth;
  const Eigen::Vector3d missing = Eigen::Vector3d::Constant(std::nan(""));
  for (int f = 40; f < 56; ++f) observed[f][b] = missing;  // b lost; from 50 a under b's label,
  for (int f = 50; f < 90; ++f) std::swap(observed[f][a], observed[f][b]);  // b back under a's at 56.
  const Result r = Repair(take, observed);
  ASSERT_FALSE(r.report.swaps.empty());
  // a's own samples are back, bit for bit, also those that came under b's label while a
  // was lost; b's, within the gap trimming, which may cut and refill a few of them
  // next to b's gap.
  for (int f = 50; f < 90; ++f) EXPECT_EQ(r.repaired[f][a], truth[f][a]) << f;
  for (int f = 50; f < 90; ++f) EXPECT_LT((r.repaired[f][b] - truth[f][b]).norm(), 2.0) << f;  // A reference refill.
  // Nothing relabelled outside the swap.
  for (const auto& [f, m] : r.relabelled) {
    EXPECT_TRUE(f >= 50 && f < 90 && (m == a || m == b)) << f << " " << m;
  }
  bool reported = false;
  for (const RepairInterval& i : r.report.detected) reported |= i.what == "swap" && i.marker == a;
  EXPECT_TRUE(reported);
}

// A swap from the take's first frame (or to its last): only one exchange event is seen,
// and the reference may follow the swapped labels from its start.
void ExpectSwapUndone(int first, int last) {
  const testing::DemoTake take = testing::MakeDemoTake(160, 60.0, 5);
  const Observations truth = Noisy(take.clean, 0.1, 10);
  const int a = take.markers.FindMarker("LeftLeg_0"), b = take.markers.FindMarker("LeftLeg_2");
  ASSERT_TRUE(a >= 0 && b >= 0);
  Observations observed = truth;
  for (int f = first; f <= last; ++f) std::swap(observed[f][a], observed[f][b]);
  const Result r = Repair(take, observed);
  for (int f = first; f <= last; ++f) {
    for (const int m : {a, b}) {
      EXPECT_TRUE(r.relabelled.count({f, m})) << f << " " << m;
      EXPECT_EQ(r.repaired[f][m], truth[f][m]) << f << " " << m;
    }
  }
  for (const auto& [f, m] : r.relabelled) {
    EXPECT_TRUE(f >= first && f <= last && (m == a || m == b)) << f << " " << m;
  }
}

TEST(SwapDetection, SwapFromTheFirstFrameIsRelabelled) { ExpectSwapUndone(0, 39); }

TEST(SwapDetection, SwapToTheLastFrameIsRelabelled) { ExpectSwapUndone(120, 159); }

TEST(SwapDetection, TwoSwapsAtOnce) {
  const testing::DemoTake take = testing::MakeDemoTake(160, 60.0, 5);
  const Observations truth = Noisy(take.clean, 0.1, 8);
  const int a = take.markers.FindMarker("LeftLeg_0"), b = take.markers.FindMarker("LeftLeg_2");
  const int c = take.markers.FindMarker("RightArm_0"), d = take.markers.FindMarker("RightArm_2");
  ASSERT_TRUE(a >= 0 && b >= 0 && c >= 0 && d >= 0);
  Observations observed = truth;
  for (int f = 30; f < 80; ++f) std::swap(observed[f][a], observed[f][b]);
  for (int f = 60; f < 120; ++f) std::swap(observed[f][c], observed[f][d]);
  const Result r = Repair(take, observed);
  int right = 0, swapped = 0;
  for (int f = 0; f < 160; ++f) {
    for (const int m : {a, b, c, d}) {
      const bool in_swap = (m == a || m == b) ? (f >= 30 && f < 80) : (f >= 60 && f < 120);
      if (!in_swap) continue;
      ++swapped;
      right += r.relabelled.count({f, m}) && r.repaired[f][m] == truth[f][m];
    }
  }
  EXPECT_GE(right, 0.95 * swapped) << right << " of " << swapped;
  for (const auto& [f, m] : r.relabelled) EXPECT_TRUE(m == a || m == b || m == c || m == d) << f << " " << m;
}

// Swaps between markers of two different bones (issue 31): the relabelled samples are kept
// bit for bit, not condemned afterwards and refilled. (A regression guard: on this demo
// fixture the joint difference did not condemn them before either; the case it did is the
// synthetic walk of scripts/synthetic_walk.py, BENCHMARKS.md.)
void ExpectCrossBoneSwapKept(const char* label_a, const char* label_b, int first, int last) {
  const testing::DemoTake take = testing::MakeDemoTake(160, 60.0, 5);
  const Observations truth = Noisy(take.clean, 0.1, 11);
  const int a = take.markers.FindMarker(label_a), b = take.markers.FindMarker(label_b);
  ASSERT_TRUE(a >= 0 && b >= 0);
  ASSERT_NE(take.markers.marker(a).attachments.front().joint, take.markers.marker(b).attachments.front().joint);
  Observations observed = truth;
  for (int f = first; f <= last; ++f) std::swap(observed[f][a], observed[f][b]);
  const Result r = Repair(take, observed);
  int kept = 0, swapped = 0;
  for (int f = first; f <= last; ++f) {
    for (const int m : {a, b}) {
      ++swapped;
      kept += r.repaired[f][m] == truth[f][m];
    }
  }
  EXPECT_GE(kept, 0.99 * swapped) << kept << " of " << swapped;
  for (const auto& [f, m] : r.relabelled) EXPECT_TRUE(m == a || m == b) << f << " " << m;
}

// A swap between markers of two bones that ends inside a gap: label a is lost over frames
// 80-95 while a's samples stay under label b until frame 89; those go back to a, bit for bit.
// (A regression guard: the claims against the reference already covered this fixture before
// the continuity pass after the exchange events; the cases it adds are on real takes.)
TEST(SwapDetection, CrossBoneSwapThatEndsInsideAGapIsRelabelled) {
  const testing::DemoTake take = testing::MakeDemoTake(160, 60.0, 5);
  const Observations truth = Noisy(take.clean, 0.1, 12);
  const int a = take.markers.FindMarker("LeftForeArm_1"), b = take.markers.FindMarker("LeftHand_1");
  ASSERT_TRUE(a >= 0 && b >= 0);
  Observations observed = truth;
  for (int f = 40; f < 90; ++f) std::swap(observed[f][a], observed[f][b]);
  for (int f = 80; f < 96; ++f) observed[f][a] = Eigen::Vector3d::Constant(std::nan(""));  // b's samples lost.
  const Result r = Repair(take, observed);
  int kept = 0;
  for (int f = 40; f < 90; ++f) kept += r.repaired[f][a] == truth[f][a];
  EXPECT_EQ(kept, 50);
  for (int f = 40; f < 80; ++f) EXPECT_EQ(r.repaired[f][b], truth[f][b]) << f;
  for (const auto& [f, m] : r.relabelled) EXPECT_TRUE(f >= 40 && f < 90 && (m == a || m == b)) << f << " " << m;
}

// Two swaps at once, one of them (a, b) starting inside a gap of a: before its start b's
// own samples stay b's, though the other swap (c, d) goes on there (judged together, its
// gain carried the pair (a, b) back into a's gap: 02_01 seed 5 of scripts/damage.py).
TEST(SwapDetection, SwapStartingInAGapBesideAnotherSwapIsNotCarriedBack) {
  const testing::DemoTake take = testing::MakeDemoTake(160, 60.0, 5);
  const Observations truth = Noisy(take.clean, 0.1, 13);
  const int a = take.markers.FindMarker("LeftForeArm_1"), b = take.markers.FindMarker("LeftHand_1");
  const int c = take.markers.FindMarker("RightLeg_0"), d = take.markers.FindMarker("RightLeg_2");
  ASSERT_TRUE(a >= 0 && b >= 0 && c >= 0 && d >= 0);
  Observations observed = truth;
  for (int f = 40; f < 80; ++f) std::swap(observed[f][c], observed[f][d]);
  for (int f = 60; f < 100; ++f) std::swap(observed[f][a], observed[f][b]);
  for (int f = 50; f < 66; ++f) observed[f][a] = Eigen::Vector3d::Constant(std::nan(""));
  const Result r = Repair(take, observed);
  for (int f = 30; f < 60; ++f) EXPECT_EQ(r.repaired[f][b], truth[f][b]) << f;
  int kept = 0;
  for (int f = 60; f < 100; ++f) kept += r.repaired[f][a] == truth[f][a];
  EXPECT_EQ(kept, 40);
  for (const auto& [f, m] : r.relabelled) {
    const bool ab = (m == a || m == b) && f >= 60 && f < 100, cd = (m == c || m == d) && f >= 40 && f < 80;
    EXPECT_TRUE(ab || cd) << f << " " << m;
  }
}

TEST(SwapDetection, CrossBoneSwapHandAndThighIsKept) { ExpectCrossBoneSwapKept("RightHand_0", "RightUpLeg_0", 50, 109); }

TEST(SwapDetection, CrossBoneSwapForearmAndHandIsKept) {
  ExpectCrossBoneSwapKept("LeftForeArm_1", "LeftHand_1", 40, 89);
}

TEST(SwapDetection, GhostBesideAWellTrackedMarkerIsNoSwap) {
  const testing::DemoTake take = testing::MakeDemoTake(160, 60.0, 5);
  const Observations truth = Noisy(take.clean, 0.1, 9);
  const int a = take.markers.FindMarker("LeftLeg_0"), b = take.markers.FindMarker("LeftLeg_2");
  Observations observed = truth;
  // a's sample becomes a point 3 mm from b, which is still tracked: a ghost, an outlier of a.
  for (int f = 60; f < 80; ++f) observed[f][a] = truth[f][b] + Eigen::Vector3d(0.3, 0, 0);
  const Result r = Repair(take, observed);
  EXPECT_TRUE(r.report.swaps.empty());
  // a cut and refilled; b stays put (Algorithm 2 may refill it too: the naive solve
  // was dragged by the ghost on their bone).
  for (int f = 60; f < 80; ++f) {
    EXPECT_LT((r.repaired[f][b] - truth[f][b]).norm(), 2.0) << f;  // A reference refill.
    EXPECT_LT((r.repaired[f][a] - truth[f][a]).norm(), 2.0) << f;
  }
}

}  // namespace
}  // namespace mocapsolve
