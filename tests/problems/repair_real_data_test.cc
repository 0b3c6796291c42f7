// Marker repair on real captures (issue 16): CMU subject 2 calibrated once on 02_01 by the
// CLI, then
//  - clean takes stay clean: 02_01 and 02_05 as captured, with either solver, have less
//    than 0.5 % of their samples replaced and no marker replaced for more than 5 % of the take;
//  - swaps made by `corrupt`'s swap damage on 02_01 are relabelled in >= 95 % of the swapped
//    samples, with <= 0.1 % of the other samples relabelled;
//  - 1-4 cm jumps and jitter on 02_01 are detected with recall and precision >= 0.9;
//  - samples moved into unlabelled tracks on 02_01 come back to their markers.
#include <set>

#include <gtest/gtest.h>

#include "settings/repair_settings.h"
#include "pipeline/subject.h"
#include "problems/marker_repair/marker_repair.h"
#include "problems/marker_repair/small_error_evaluation.h"
#include "signal/marker_corruption.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

using Observations = std::vector<std::vector<Eigen::Vector3d>>;

class RepairRealData : public ::testing::Test {
 protected:
  void SetUp() override {
    MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
    MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
    MOCAPSOLVE_DATA_FILE(c3d, "c3d/02_01.c3d");
    MOCAPSOLVE_DATA_FILE(take, "c3d/cmu_02_05.c3d");
    c3d_ = c3d;
    c3d_0205_ = take;
    const std::string path = testing::TempPath("S02.json");
    std::string output;
    ASSERT_EQ(testing::RunCli("calibrate --quiet --motion=" + amc + " --skeleton=" + asf + " --markers=" + c3d +
                              " --axes=y,z,x --out=" + testing::TempPath("02.json") + " --out_subject=" + path,
                              &output), 0) << output;
    ASSERT_TRUE(ReadSubject(path, &subject_).ok());
  }

  RepairOptions Options(const std::string& solver) const {
    SolverSettings settings;
    settings.solver = solver;
    RepairOptions options;
    const Status status = RepairOptionsFromSettings(RepairSettings(), settings, subject_.skeleton, &options);
    EXPECT_TRUE(status.ok()) << status.message();
    return options;
  }

  Observations Load(const std::string& path) const {
    MarkerTake take;
    const Status status = LoadTakeForSubject(subject_, path, &take);
    EXPECT_TRUE(status.ok()) << status.message();
    return take.observed;
  }

  double CmPerUnit() const { return subject_.skeleton.unit().metres_per_unit * 100.0; }

  Subject subject_;
  std::string c3d_, c3d_0205_;
};

bool Same(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.allFinite() ? a == b : !b.allFinite(); }

TEST_F(RepairRealData, CleanTakesStayClean) {
  for (const std::string& path : {c3d_, c3d_0205_}) {
    const Observations observed = Load(path);
    for (const char* solver : {"dls", "ceres"}) {
      Observations repaired;
      Motion motion;
      RepairReport report;
      ASSERT_TRUE(RepairMarkers(subject_.skeleton, subject_.markers, observed, Options(solver), &repaired, &motion,
                                &report).ok());
      const int nf = static_cast<int>(observed.size()), nm = subject_.markers.num_markers();
      int replaced = 0, worst = 0, worst_marker = 0;
      for (int m = 0; m < nm; ++m) {
        int count = 0;
        for (int f = 0; f < nf; ++f) count += observed[f][m].allFinite() && !Same(repaired[f][m], observed[f][m]);
        replaced += count;
        if (count > worst) worst = count, worst_marker = m;
      }
      std::printf("%s %s: %.3f %% of samples replaced, worst marker %s %.1f %% of the take\n", path.c_str(), solver,
                  100.0 * replaced / (nf * nm), subject_.markers.label(worst_marker).c_str(), 100.0 * worst / nf);
      // The targets: under 0.5 % of samples, no marker over 5 % of the take, either
      // solver (measured 0.014-0.146 % and 0.3-3.2 %, BENCHMARKS.md).
      EXPECT_LT(replaced, 0.005 * nf * nm) << path << " " << solver;
      EXPECT_LE(worst, 0.05 * nf) << path << " " << solver;
      EXPECT_TRUE(report.swaps.empty()) << path << " " << solver;
    }
  }
}

TEST_F(RepairRealData, SwapsAreRelabelled) {
  const Observations clean = Load(c3d_);
  const double cm = CmPerUnit();
  long swapped = 0, right = 0, wrong = 0, others = 0;
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    MarkerTrajectories x = ObservationTrajectories(subject_.markers, clean);
    CorruptionOptions damage;  // Swaps only: 3 of 40 frames with the nearest marker within 20 cm.
    damage.seed = seed;
    damage.gaps = damage.cluster_gaps = damage.noisy_markers = 0;
    damage.swaps = 3;
    damage.swap_length = 40;
    damage.swap_radius = 20.0 / cm;
    CorruptionMask mask;
    CorruptMarkers(damage, &x, &mask);
    Observations repaired;
    Motion motion;
    RepairReport report;
    ASSERT_TRUE(RepairMarkers(subject_.skeleton, subject_.markers, TrajectoryObservations(x), Options("dls"),
                              &repaired, &motion, &report).ok());
    std::set<std::pair<int, int>> relabelled;
    for (const MarkerSwap& swap : report.swaps) {
      for (int f = swap.first; f <= swap.last; ++f) {
        for (const auto& [from, to] : swap.from_to) relabelled.insert({f, to});
      }
    }
    for (size_t f = 0; f < clean.size(); ++f) {
      for (int m = 0; m < subject_.markers.num_markers(); ++m) {
        const bool hit = relabelled.count({int(f), m}) > 0;
        // Two swaps of one pair that overlap give the overlap back its own samples
        // (seed 4, LANK and LHEE): marked 's' but unmoved, nothing to relabel there.
        if (mask[f][m] == 's' && !Same(x.position(int(f), m), clean[f][m])) {
          ++swapped;
          right += hit && repaired[f][m] == clean[f][m];
        } else {  // Also the overlap's samples: none may be relabelled.
          ++others;
          wrong += hit;
        }
      }
    }
  }
  std::printf("swapped samples relabelled %ld of %ld (%.1f %%), other samples relabelled %ld of %ld (%.3f %%)\n",
              right, swapped, 100.0 * right / swapped, wrong, others, 100.0 * wrong / others);
  // The target is 95 %; measured 99.9 % (1,047 of 1,048; BENCHMARKS.md).
  EXPECT_GE(right, 0.99 * swapped);
  EXPECT_LE(wrong, 0.001 * others);
}

// Labels dropped (issue 16 item 3): `corrupt`'s unlabelled damage on 02_01 (4 runs of 40
// frames per seed, with 5 gaps) moves samples into unlabelled tracks; the repair must give
// them back to their own markers and none to another.
TEST_F(RepairRealData, UnlabelledSamplesAreRestored) {
  const Observations clean = Load(c3d_);
  const double cm = CmPerUnit();
  long moved = 0, assigned = 0, restored = 0, wrong = 0;
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    MarkerTrajectories x = ObservationTrajectories(subject_.markers, clean);
    CorruptionOptions damage;
    damage.seed = seed;
    damage.cluster_gaps = damage.swaps = damage.noisy_markers = 0;
    damage.gaps = 5;
    damage.fly_off_distance = 0.0;
    damage.cluster_radius = 15.0 / cm;
    damage.unlabels = 4;
    damage.unlabel_length = 40;
    CorruptionMask mask;
    UnlabelledDamage unlabelled;
    CorruptMarkers(damage, &x, &mask, &unlabelled);
    UnlabelledPoints points;
    points.names = unlabelled.tracks.labels();
    points.points = TrajectoryObservations(unlabelled.tracks);
    Observations repaired;
    Motion motion;
    RepairReport report;
    ASSERT_TRUE(RepairMarkers(subject_.skeleton, subject_.markers, TrajectoryObservations(x), points, Options("dls"),
                              &repaired, &motion, &report).ok());
    for (const UnlabelledAssignment& a : report.unlabelled) {
      if (a.marker != unlabelled.source[a.track]) {
        wrong += a.last - a.first + 1;
        continue;
      }
      for (int f = a.first; f <= a.last; ++f) assigned += mask[f][a.marker] == 'u';
    }
    for (size_t f = 0; f < clean.size(); ++f) {
      for (int m = 0; m < subject_.markers.num_markers(); ++m) {
        if (mask[f][m] != 'u') continue;
        ++moved;
        restored += repaired[f][m] == clean[f][m];
      }
    }
  }
  std::printf("unlabelled samples assigned to their marker %ld of %ld (%.1f %%), to another marker %ld; kept in the "
              "output %ld (%.1f %%)\n", assigned, moved, 100.0 * assigned / moved, wrong, restored,
              100.0 * restored / moved);
  EXPECT_GE(assigned, 0.9 * moved);  // Measured 96.2 %.
  EXPECT_EQ(wrong, 0);
  // Trimming beside the gaps next to the runs (up to --trim_max frames, the thesis' rule for
  // any sample at a gap's edge) cuts some assigned samples again: measured 75.3 %.
  EXPECT_GE(restored, 0.7 * moved);
}

TEST_F(RepairRealData, SmallErrorsAreFound) {
  // The recipe (12 jumps of 1-4 cm lasting 1-20 frames and 3 runs of 2 cm jitter of 10
  // frames per seed) and its scoring: small_error_evaluation.h, as `evaluate
  // --method=small_errors` runs them.
  SmallErrorScore score;
  SmallErrorRecipe recipe = DefaultSmallErrorRecipe(subject_.skeleton.unit().metres_per_unit);
  ASSERT_TRUE(EvaluateSmallErrors(subject_.skeleton, subject_.markers, Load(c3d_), Options("dls"), recipe, 3, &score)
                  .ok());
  std::printf("1-4 cm errors: %ld samples, recall %.3f, precision %.3f (%.3f without the %ld samples also flagged "
              "on the undamaged take)\n", score.damaged, score.Recall(), score.Precision(), score.PrecisionWithoutOwn(),
              score.own);
  // The target is 0.9 / 0.9; measured 0.930 / 0.926 (0.906 / 0.924 before the
  // windowed plateaus, 0.844 / 0.919 before the calm plateaus, 0.736 / 0.927 before the
  // steps seen from the joint's parent and the sharp pairs; BENCHMARKS.md).
  EXPECT_GE(score.Recall(), 0.9);
  EXPECT_GE(score.Precision(), 0.9);
}

}  // namespace
}  // namespace mocapsolve
