// The repair pipeline on markers synthesized from the demo walk, with a natural-style gap
// and a marker that flies off: the gap is refilled close to the truth, the flying marker
// is detected (as an outlier against the robust reference) and replaced, the rest is
// untouched.
#include "problems/marker_repair/marker_repair.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/sequence_solver.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "tests/problems/repair_test_support.h"

namespace mocapsolve {
namespace {

void CheckRepair(ReferenceKind reference_kind, GapFillKind fill = GapFillKind::kKriging) {
  const testing::DemoTake take = testing::MakeDemoTake(120, 60.0, 5);
  const Skeleton& skeleton = take.skeleton;
  const Motion& truth = take.truth;
  const MarkerSet& markers = take.markers;
  const auto& clean = take.clean;
  auto corrupted = clean;
  const int gap_marker = markers.FindMarker("LeftForeArm_1");
  const int fly_marker = markers.FindMarker("RightForeArm_0");
  ASSERT_GE(gap_marker, 0);
  ASSERT_GE(fly_marker, 0);
  for (int f = 40; f < 70; ++f) corrupted[f][gap_marker] = Eigen::Vector3d::Constant(std::nan(""));
  for (int f = 80; f < 95; ++f) corrupted[f][fly_marker] += Eigen::Vector3d(0, 40, 0);  // 40 cm off.

  RepairOptions options = testing::DemoRepairOptions(reference_kind);
  options.outlier_distance = 0.0;  // Outliers at dp_max, as the thesis' joint threshold.
  options.trim_max = 10;
  options.small_track = 10;
  options.small_gap = 3;
  options.fill = fill;
  std::vector<std::vector<Eigen::Vector3d>> repaired;
  Motion motion;
  RepairReport report;
  const Status status = RepairMarkers(skeleton, markers, corrupted, options, &repaired, &motion, &report);
  ASSERT_TRUE(status.ok()) << status.message();

  bool detected_fly = false;
  for (const RepairInterval& interval : report.detected) {
    if (interval.marker == fly_marker && interval.what != "missing" && interval.first <= 85 && interval.last >= 90) {
      detected_fly = true;
    }
  }
  EXPECT_TRUE(detected_fly);
  double worst_gap = 0.0, worst_fly = 0.0;
  for (int f = 40; f < 70; ++f) worst_gap = std::max(worst_gap, (repaired[f][gap_marker] - clean[f][gap_marker]).norm());
  for (int f = 80; f < 95; ++f) worst_fly = std::max(worst_fly, (repaired[f][fly_marker] - clean[f][fly_marker]).norm());
  // Noise-free data, a robust reference: the refills land within a few mm of the truth
  // (cm units), far from the 40 cm excursion.
  EXPECT_LT(worst_gap, 0.5);
  EXPECT_LT(worst_fly, 2.0);
  // Markers far from the damage are returned as they came.
  const int head = markers.FindMarker("Head_0");
  for (int f = 0; f < truth.num_frames(); ++f) EXPECT_EQ(repaired[f][head], corrupted[f][head]) << f;
  EXPECT_EQ(report.timings.size(), reference_kind == ReferenceKind::kClip ? 9u : 8u);
  EXPECT_LT(report.repaired_rms, report.naive_rms);

  // Step 7 re-solves only where the markers changed (and until it rejoins the naive
  // solve); the result is the full per-frame solve of the repaired markers.
  EXPECT_LT(report.resolved_frames, truth.num_frames());
  Motion full;
  SequenceSolveReport sequence;
  ASSERT_TRUE(SolveSequence(skeleton, markers, repaired, options.naive, RestPose(skeleton), &full, &sequence).ok());
  FkData a(skeleton), b(skeleton);
  double worst = 0.0;
  for (int f = 0; f < truth.num_frames(); ++f) {
    ForwardKinematics(skeleton, full.frames[f], &a);
    ForwardKinematics(skeleton, motion.frames[f], &b);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      worst = std::max(worst, (a.world_positions[j] - b.world_positions[j]).norm());
    }
  }
  // The re-solve rejoins the naive solve within dp_max * 1e-3 (0.1 mm) and starts its
  // second half from the naive pose: 0.1 mm apart at most (cm units).
  EXPECT_LT(worst, 1e-2);
}

TEST(MarkerRepair, RefillsGapsAndReplacesAFlyingMarkerWithTheClipReference) {
  CheckRepair(ReferenceKind::kClip);
}

TEST(MarkerRepair, RefillsGapsAndReplacesAFlyingMarkerWithTheTrackerReference) {
  CheckRepair(ReferenceKind::kTracker);
}

// The defaults fill by kriging the offset from the reference (signal/offset_kriging.h);
// Algorithm 3's blend meets the same bounds.
TEST(MarkerRepair, RefillsGapsAndReplacesAFlyingMarkerByTheEdgeBlend) {
  CheckRepair(ReferenceKind::kTracker, GapFillKind::kBlend);
}

// Two neighbouring markers exchange places for 20 frames (a labelling swap): both are
// outliers against the reference and come back near their true paths; a gap at each end
// of the take and a one-frame gap are refilled too.
TEST(MarkerRepair, UndoesASwapAndFillsGapsAtTheEndsAndOfOneFrame) {
  const testing::DemoTake take = testing::MakeDemoTake(120, 60.0, 5);
  const Skeleton& skeleton = take.skeleton;
  const MarkerSet& markers = take.markers;
  const auto& clean = take.clean;
  auto corrupted = clean;
  const int a = markers.FindMarker("LeftLeg_0"), b = markers.FindMarker("LeftLeg_2");
  const int ends = markers.FindMarker("RightArm_1"), one = markers.FindMarker("Head_1");
  ASSERT_TRUE(a >= 0 && b >= 0 && ends >= 0 && one >= 0);
  for (int f = 50; f < 70; ++f) std::swap(corrupted[f][a], corrupted[f][b]);
  const Eigen::Vector3d missing = Eigen::Vector3d::Constant(std::nan(""));
  for (int f = 0; f < 8; ++f) corrupted[f][ends] = missing;
  for (int f = 112; f < 120; ++f) corrupted[f][ends] = missing;
  corrupted[30][one] = missing;

  RepairOptions options = testing::DemoRepairOptions(ReferenceKind::kTracker);
  options.trim_max = 5;
  options.small_track = 5;
  options.small_gap = 0;  // So the one-frame gap goes through the reference fill.
  std::vector<std::vector<Eigen::Vector3d>> repaired;
  Motion motion;
  RepairReport report;
  ASSERT_TRUE(RepairMarkers(skeleton, markers, corrupted, options, &repaired, &motion, &report).ok());
  ASSERT_GT((clean[60][a] - clean[60][b]).norm(), 4.0);  // The swap moves them past the outlier test.
  double worst = 0.0;
  for (int f = 50; f < 70; ++f) {
    worst = std::max({worst, (repaired[f][a] - clean[f][a]).norm(), (repaired[f][b] - clean[f][b]).norm()});
  }
  EXPECT_LT(worst, 1.0);  // cm: back on their own paths, not the swapped ones.
  for (int f : {0, 5, 7, 112, 119}) EXPECT_LT((repaired[f][ends] - clean[f][ends]).norm(), 1.0) << f;
  EXPECT_LT((repaired[30][one] - clean[30][one]).norm(), 0.5);
}

// One sample missing from a clean, noisy track (a point the labeller left unlabelled, a
// one-frame dropout): smart trimming stops at the first edge as good as the rest of the
// track, instead of at the smallest slope difference among trim_max candidates (which,
// with noise, lay anywhere up to 120 frames away and replaced that many captured samples).
TEST(MarkerRepair, OneMissingSampleOfACleanTrackCutsLittle) {
  const testing::DemoTake take = testing::MakeDemoTake(240, 120.0, 5);
  auto noisy = take.clean;
  std::uint32_t state = 12345;
  auto uniform = [&state]() {  // Deterministic noise of +-0.1 cm per axis.
    state = state * 1664525u + 1013904223u;
    return (static_cast<double>(state >> 8) / 16777216.0 - 0.5) * 0.2;
  };
  for (auto& frame : noisy) {
    for (Eigen::Vector3d& p : frame) p += Eigen::Vector3d(uniform(), uniform(), uniform());
  }
  const int marker = take.markers.FindMarker("LeftForeArm_1");
  ASSERT_GE(marker, 0);
  auto corrupted = noisy;
  corrupted[120][marker] = Eigen::Vector3d::Constant(std::nan(""));
  const RepairOptions options = testing::DemoRepairOptions(ReferenceKind::kTracker);  // trim_max 120.
  ASSERT_EQ(options.trim_max, 120);
  std::vector<std::vector<Eigen::Vector3d>> repaired;
  Motion motion;
  RepairReport report;
  ASSERT_TRUE(RepairMarkers(take.skeleton, take.markers, corrupted, options, &repaired, &motion, &report).ok());
  int replaced = 0;
  for (int f = 0; f < 240; ++f) replaced += f != 120 && !(repaired[f][marker] == corrupted[f][marker]);
  EXPECT_LE(replaced, 10) << "captured samples of the track replaced around a one-sample gap";
  EXPECT_LT((repaired[120][marker] - take.clean[120][marker]).norm(), 0.5);
}

// A whole foot hidden (every marker of the foot and toe for 40 frames of the walk): the
// foot and toe are reported carried over the gap, and their markers come back closer to
// the truth than the fill without the carry, which leaves the unobserved joints where the
// reference's solve without data put them.
TEST(MarkerRepair, CarriesTheJointsOfAHiddenFootAcrossTheGap) {
  const testing::DemoTake take = testing::MakeDemoTake(120, 60.0, 5);
  const Skeleton& skeleton = take.skeleton;
  const MarkerSet& markers = take.markers;
  auto corrupted = take.clean;
  const int foot = skeleton.FindJoint("LeftFoot");
  std::vector<int> hidden;
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (const MarkerAttachment& a : markers.marker(m).attachments) {
      if (skeleton.IsAncestorOrSelf(foot, a.joint)) hidden.push_back(m);
    }
  }
  ASSERT_GE(hidden.size(), 3u);
  for (int f = 40; f < 80; ++f) {
    for (int m : hidden) corrupted[f][m] = Eigen::Vector3d::Constant(std::nan(""));
  }
  auto worst_error = [&](bool carry, RepairReport* report) {
    RepairOptions options = testing::DemoRepairOptions(ReferenceKind::kTracker);
    options.carry_joints = carry;
    std::vector<std::vector<Eigen::Vector3d>> repaired;
    Motion motion;
    EXPECT_TRUE(RepairMarkers(skeleton, markers, corrupted, options, &repaired, &motion, report).ok());
    double worst = 0.0;
    for (int f = 40; f < 80; ++f) {
      for (int m : hidden) worst = std::max(worst, (repaired[f][m] - take.clean[f][m]).norm());
    }
    return worst;
  };
  RepairReport with, without;
  const double carried = worst_error(true, &with), plain = worst_error(false, &without);
  EXPECT_TRUE(without.carried.empty());
  bool foot_carried = false;
  for (const CarriedJointRun& run : with.carried) {
    foot_carried |= run.joint == foot && run.first <= 40 && run.last >= 79;
    EXPECT_TRUE(skeleton.IsAncestorOrSelf(skeleton.parent(foot), run.joint)) << skeleton.name(run.joint);
  }
  EXPECT_TRUE(foot_carried);
  EXPECT_LT(carried, plain);
  EXPECT_LT(carried, 3.0);  // cm, noise-free walk.
}

// The same hidden foot, the naive solve holding hidden joints at a reference pose (as a
// subject's mean pose does in `pipeline`): the report counts the frames each was held, the
// foot's 40 and none for a joint whose markers were all seen.
TEST(MarkerRepair, ReportsTheHiddenJointsItsNaiveSolveHeld) {
  const testing::DemoTake take = testing::MakeDemoTake(120, 60.0, 5);
  const Skeleton& skeleton = take.skeleton;
  const int foot = skeleton.FindJoint("LeftFoot");
  auto corrupted = take.clean;
  for (int m = 0; m < take.markers.num_markers(); ++m) {
    for (const MarkerAttachment& a : take.markers.marker(m).attachments) {
      if (!skeleton.IsAncestorOrSelf(foot, a.joint)) continue;
      for (int f = 40; f < 80; ++f) corrupted[f][m] = Eigen::Vector3d::Constant(std::nan(""));
    }
  }
  RepairOptions options = testing::DemoRepairOptions(ReferenceKind::kTracker);
  options.naive.rest_rotations.assign(skeleton.num_joints(), Eigen::Quaterniond::Identity());
  options.naive.hidden_rotation_weight = 1.0;
  std::vector<std::vector<Eigen::Vector3d>> repaired;
  Motion motion;
  RepairReport report;
  ASSERT_TRUE(RepairMarkers(skeleton, take.markers, corrupted, options, &repaired, &motion, &report).ok());
  ASSERT_EQ(report.naive_held_frames.size(), static_cast<size_t>(skeleton.num_joints()));
  EXPECT_EQ(report.naive_held_frames[foot], 40);
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    if (!skeleton.IsAncestorOrSelf(foot, j)) {
      EXPECT_EQ(report.naive_held_frames[j], 0) << skeleton.name(j);
    }
  }
}

// Threads change the speed only: one thread gives the same markers and motion, bit for
// bit, as two (a batch runs its takes single-threaded, side by side).
TEST(MarkerRepair, ResultDoesNotDependOnThreads) {
  const testing::DemoTake take = testing::MakeDemoTake(120, 60.0, 5);
  auto corrupted = take.clean;
  const int marker = take.markers.FindMarker("LeftForeArm_1");
  ASSERT_GE(marker, 0);
  for (int f = 20; f < 100; f += 3) corrupted[f][marker] += Eigen::Vector3d(0, 10, 0);  // Outliers across both halves.
  std::vector<std::vector<Eigen::Vector3d>> repaired[2];
  Motion motion[2];
  for (int threads = 1; threads <= 2; ++threads) {
    RepairOptions options = testing::DemoRepairOptions(ReferenceKind::kTracker);
    options.parallel = threads == 2;
    RepairReport report;
    ASSERT_TRUE(RepairMarkers(take.skeleton, take.markers, corrupted, options, &repaired[threads - 1],
                              &motion[threads - 1], &report).ok());
    EXPECT_GT(report.resolved_frames, 60);  // Both halves re-solved.
  }
  for (int f = 0; f < motion[0].num_frames(); ++f) {
    for (int j = 0; j < take.skeleton.num_joints(); ++j) {
      EXPECT_EQ(motion[0].frames[f].rotations[j].coeffs(), motion[1].frames[f].rotations[j].coeffs()) << f << " " << j;
      EXPECT_EQ(motion[0].frames[f].translations[j], motion[1].frames[f].translations[j]) << f << " " << j;
    }
  }
  EXPECT_EQ(repaired[0], repaired[1]);
}

// Issue 15: NaN, inf and negative values are refused in one place, the options' IsValid.
TEST(MarkerRepair, OptionsRejectNonFiniteAndNegativeValues) {
  std::string error;
  RepairOptions options = testing::DemoRepairOptions(ReferenceKind::kTracker);
  ASSERT_TRUE(options.IsValid(&error)) << error;
  const double nan = std::nan("");
  auto invalid = [&](auto change) {
    RepairOptions o = testing::DemoRepairOptions(ReferenceKind::kTracker);
    change(&o);
    return !o.IsValid(&error) && !error.empty();
  };
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->velocity_clamp = nan; }));
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->small_gap = -1; }));
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->trim_max = -1; }));
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->fill_samples = 0; }));
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->refit_rough_factor = nan; }));
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->rough_extension_factor = -1.0; }));
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->rough_extension_factor = nan; }));
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->dp_max = nan; }));
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->naive.prior_rotation_weight = nan; }));
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->tracker.limit_weight = nan; }));
  EXPECT_TRUE(invalid([&](RepairOptions* o) { o->naive.marker_weight = std::numeric_limits<double>::infinity(); }));
  ClipSolveOptions clip;
  clip.rotation_smoothness = nan;
  EXPECT_FALSE(clip.IsValid(&error));
}

// A take of 0 frames (or frames of the wrong marker count) is refused with one line, not
// solved into an empty motion that later stages index (the CLI and Python crashed).
TEST(MarkerRepair, RejectsATakeWithoutFramesOrOfTheWrongMarkerCount) {
  const testing::DemoTake take = testing::MakeDemoTake(4, 30.0, 3);
  const RepairOptions options = testing::DemoRepairOptions(ReferenceKind::kTracker);
  std::vector<std::vector<Eigen::Vector3d>> repaired;
  Motion motion;
  RepairReport report;
  Status status = RepairMarkers(take.skeleton, take.markers, {}, options, &repaired, &motion, &report);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("no frames"), std::string::npos) << status.message();
  EXPECT_EQ(status.message().find('\n'), std::string::npos);
  std::vector<std::vector<Eigen::Vector3d>> short_frame = take.clean;
  short_frame[2].pop_back();
  status = RepairMarkers(take.skeleton, take.markers, short_frame, options, &repaired, &motion, &report);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("frame 2"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace mocapsolve
