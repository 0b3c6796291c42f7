// Motions and markers through the pyramid: rotations as sign-continuous quaternions,
// missing marker samples kept missing, and denoising of real markers (02_01.c3d).
#include "signal/motion_pyramid.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "io/marker_file.h"
#include "kinematics/demo_character.h"
#include "kinematics/rotation.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

double MaxRotationError(const Motion& a, const Motion& b) {
  double worst = 0.0;
  for (int f = 0; f < a.num_frames(); ++f) {
    for (size_t j = 0; j < a.frames[f].rotations.size(); ++j) {
      worst = std::max(worst, AngularDistance(a.frames[f].rotations[j], b.frames[f].rotations[j]));
    }
  }
  return worst;
}

double MaxTranslationError(const Motion& a, const Motion& b) {
  double worst = 0.0;
  for (int f = 0; f < a.num_frames(); ++f) {
    for (size_t j = 0; j < a.frames[f].translations.size(); ++j) {
      worst = std::max(worst, (a.frames[f].translations[j] - b.frames[f].translations[j]).norm());
    }
  }
  return worst;
}

// The demo walk with its root spinning about Y by `rate` rad per frame.
Motion SpinningWalk(const Skeleton& skeleton, int frames, double rate = 0.2) {
  Motion motion = MakeDemoWalk(skeleton, frames, 60.0);
  for (int f = 0; f < frames; ++f) {
    Eigen::Quaterniond& root = motion.frames[f].rotations[0];
    root = Eigen::Quaterniond(Eigen::AngleAxisd(rate * f, Eigen::Vector3d::UnitY())) * root;
  }
  MakeSignContinuous(&motion);
  return motion;
}

TEST(MotionPyramid, AllOnesReturnsTheMotion) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = SpinningWalk(skeleton, 101);
  Motion out;
  ASSERT_TRUE(FilterMotion(motion, PyramidOptions(), {}, &out).ok());
  ASSERT_EQ(out.num_frames(), motion.num_frames());
  EXPECT_EQ(out.frame_rate, motion.frame_rate);
  EXPECT_LT(MaxRotationError(motion, out), 1e-9);
  EXPECT_LT(MaxTranslationError(motion, out), 1e-9);
}

TEST(MotionPyramid, ManyTurnsFilterSmoothly) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = SpinningWalk(skeleton, 120);  // About 4 turns of the root.
  Signal signal;
  MotionToSignal(motion, ReferenceRotations(motion, 0), 0, &signal);
  // Sign-continuous quaternion channels: |dq| ~ 0.2 rad / 2 per frame, never a flip.
  for (int f = 1; f < signal.rows(); ++f) {
    EXPECT_LT((signal.block<1, 4>(f, 0) - signal.block<1, 4>(f - 1, 0)).norm(), 0.2) << f;
  }
  // Dropping the finest bands keeps the root spinning smoothly (no flips): the result
  // stays within a few degrees of the input.
  PyramidOptions options;
  options.levels = 2;
  Motion smooth;
  ASSERT_TRUE(FilterMotion(motion, options, DropFinestBands(2, 2), &smooth).ok());
  EXPECT_LT(MaxRotationError(motion, smooth), 0.1);
}

TEST(MotionPyramid, BadOptionsAreErrors) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = MakeDemoWalk(skeleton, 10, 30.0);
  Motion out;
  PyramidOptions options;
  options.levels = 9;
  EXPECT_FALSE(FilterMotion(motion, options, {}, &out).ok());
  options.levels = 2;
  EXPECT_FALSE(FilterMotion(motion, options, {1.0, 1.0}, &out).ok());
  options.tension = 2.0;
  EXPECT_FALSE(FilterMotion(motion, options, {}, &out).ok());
}

MarkerTrajectories SineMarkers(int frames) {
  MarkerTrajectories markers({"A", "B", "C"}, frames);
  markers.frame_rate = 100.0;
  markers.unit = {"mm", 0.001};
  for (int f = 0; f < frames; ++f) {
    for (int m = 0; m < 3; ++m) {
      markers.SetSample(f, m, Eigen::Vector3d(100.0 * std::sin(0.05 * f + m), 10.0 * m, 0.5 * f));
    }
  }
  return markers;
}

TEST(MotionPyramid, MissingMarkerSamplesStayMissing) {
  MarkerTrajectories markers = SineMarkers(80);
  for (int f = 10; f < 20; ++f) markers.SetMissing(f, 0);  // A gap.
  for (int f = 0; f < 5; ++f) markers.SetMissing(f, 1);    // Missing at the start.
  for (int f = 0; f < 80; ++f) markers.SetMissing(f, 2);   // Never seen.
  MarkerTrajectories out;
  ASSERT_TRUE(FilterMarkers(markers, PyramidOptions(), {}, &out).ok());
  EXPECT_EQ(out.valid_mask(), markers.valid_mask());
  EXPECT_EQ(out.CountMissing(), markers.CountMissing());
  for (int f = 0; f < 80; ++f) {
    for (int m = 0; m < 3; ++m) {
      if (!markers.valid(f, m)) {
        EXPECT_TRUE(out.position(f, m).array().isNaN().all());
        continue;
      }
      EXPECT_LT((out.position(f, m) - markers.position(f, m)).norm(), 1e-9);
    }
  }
  // Smoothing across the gap: the filled gap is a straight segment, the output stays
  // near the sine next to it.
  PyramidOptions options;
  options.levels = 2;
  ASSERT_TRUE(FilterMarkers(markers, options, DropFinestBands(2, 2), &out).ok());
  EXPECT_EQ(out.valid_mask(), markers.valid_mask());
  EXPECT_LT((out.position(25, 0) - markers.position(25, 0)).norm(), 1.0);
}

// Denoising real markers: Gaussian noise on 02_01.c3d, then the pyramid without its
// finest bands; the error to the clean markers must drop. Prints the figures per level.
TEST(MotionPyramid, DenoisesRealMarkers) {
  MOCAPSOLVE_DATA_FILE(path, "c3d/02_01.c3d");
  MarkerTrajectories clean;
  ASSERT_TRUE(ReadMarkerFile(path, &clean).ok());
  ASSERT_TRUE(ConvertUnits({"mm", 0.001}, &clean).ok());
  const double sigma_mm = 3.0;  // Per axis.
  MarkerTrajectories noisy = clean;
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, sigma_mm);
  for (int f = 0; f < clean.num_frames(); ++f) {
    for (int m = 0; m < clean.num_markers(); ++m) {
      if (!clean.valid(f, m)) continue;
      noisy.SetSample(f, m, clean.position(f, m) +
                                Eigen::Vector3d(normal(rng), normal(rng), normal(rng)));
    }
  }
  auto rms_to_clean = [&](const MarkerTrajectories& t) {
    double sum = 0.0;
    int count = 0;
    for (int f = 0; f < t.num_frames(); ++f) {
      for (int m = 0; m < t.num_markers(); ++m) {
        if (!clean.valid(f, m)) continue;
        sum += (t.position(f, m) - clean.position(f, m)).squaredNorm();
        ++count;
      }
    }
    return std::sqrt(sum / count);
  };
  const double before = rms_to_clean(noisy);
  std::printf("02_01.c3d: %d frames at %g Hz, %d markers, %g mm noise per axis: rms %.3f mm\n",
              clean.num_frames(), clean.frame_rate, clean.num_markers(), sigma_mm, before);
  double best = before;
  for (int levels = 1; levels <= 4; ++levels) {
    PyramidOptions options;
    options.levels = levels;
    MarkerTrajectories filtered;
    ASSERT_TRUE(FilterMarkers(noisy, options, DropFinestBands(levels, levels), &filtered).ok());
    EXPECT_EQ(filtered.valid_mask(), noisy.valid_mask());
    const double after = rms_to_clean(filtered);
    std::printf("  drop %d finest band(s): rms to clean %.3f mm\n", levels, after);
    best = std::min(best, after);
    if (levels <= 2) {
      EXPECT_LT(after, before) << levels;
    }
  }
  EXPECT_LT(best, 0.6 * before);
}

}  // namespace
}  // namespace mocapsolve
