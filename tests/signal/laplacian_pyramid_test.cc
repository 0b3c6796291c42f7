// The pyramid's algebra: kernel constraints (eq. 1), exact reconstruction (eq. 4) at any
// length, straight lines kept, band editing (eq. 7) and where a sinusoid lands.
#include "signal/laplacian_pyramid.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

Signal RandomSignal(int rows, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 100.0);
  Signal signal(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int c = 0; c < cols; ++c) signal(i, c) = normal(rng);
  }
  return signal;
}

TEST(GeneratingKernel, NormalizedSymmetricEqualContribution) {
  for (double a : {0.25, 0.3, 0.375, 0.4, 0.5, 0.6}) {
    const GeneratingKernel kernel{a};
    ASSERT_TRUE(kernel.Validate().ok());
    const auto w = kernel.weights();
    EXPECT_NEAR(w[0] + w[1] + w[2] + w[3] + w[4], 1.0, 1e-15);
    EXPECT_EQ(w[0], w[4]);
    EXPECT_EQ(w[1], w[3]);
    // Every level-l node gives the same total weight to level l+1: even nodes a + 2c,
    // odd nodes 2b.
    EXPECT_NEAR(w[2] + w[0] + w[4], w[1] + w[3], 1e-15);
    EXPECT_NEAR(w[1] + w[3], 0.5, 1e-15);
  }
  EXPECT_FALSE(GeneratingKernel{0.9}.Validate().ok());
  EXPECT_FALSE(GeneratingKernel{0.1}.Validate().ok());
}

TEST(GeneratingKernel, ReduceSpreadsEqualWeightFromEveryInteriorNode) {
  // REDUCE of a unit impulse at an interior node: total weight 1/2 whether the node
  // sits under a coarse sample (even) or between two (odd).
  const GeneratingKernel kernel;
  for (int node : {20, 21}) {
    Signal impulse = Signal::Zero(41, 1);
    impulse(node, 0) = 1.0;
    Signal coarse;
    Reduce(impulse, kernel, &coarse);
    EXPECT_NEAR(coarse.sum(), 0.5, 1e-15) << "node " << node;
  }
}

TEST(LaplacianPyramid, LevelSizes) {
  EXPECT_EQ(MaxPyramidLevels(1), 0);
  EXPECT_EQ(MaxPyramidLevels(2), 0);
  EXPECT_EQ(MaxPyramidLevels(3), 1);
  EXPECT_EQ(MaxPyramidLevels(17), 4);  // 17, 9, 5, 3, 2 (the paper's 2^4 + 1 has 4 layers
                                       // plus one more step down to 2 samples).
  EXPECT_EQ(PyramidLevelSize(17, 2), 5);
  EXPECT_EQ(PyramidLevelSize(10, 1), 5);
  Signal signal = RandomSignal(10, 2, 1);
  LaplacianPyramid pyramid;
  EXPECT_FALSE(BuildLaplacianPyramid(signal, PyramidOptions{{0.4}, 0.0, 9}, &pyramid).ok());
  ASSERT_TRUE(BuildLaplacianPyramid(signal, PyramidOptions(), &pyramid).ok());
  EXPECT_EQ(pyramid.levels(), MaxPyramidLevels(10));
  EXPECT_EQ(pyramid.laplacian[0].rows(), 10);
  EXPECT_EQ(pyramid.top().rows(), 2);
}

TEST(LaplacianPyramid, ReconstructionIsExactAtAnyLength) {
  for (int rows : {3, 4, 5, 6, 17, 33, 100, 101, 1000}) {
    for (double tension : {0.0, 0.5}) {
      for (double a : {0.375, 0.4, 0.6}) {
        const Signal signal = RandomSignal(rows, 3, rows);
        PyramidOptions options;
        options.kernel.a = a;
        options.tension = tension;
        LaplacianPyramid pyramid;
        ASSERT_TRUE(BuildLaplacianPyramid(signal, options, &pyramid).ok());
        Signal out;
        ReconstructSignal(pyramid, {}, &out);
        ASSERT_EQ(out.rows(), rows);
        // Rounding only: values ~100, a dozen levels of 4-tap sums.
        EXPECT_LT((out - signal).cwiseAbs().maxCoeff(), 1e-9)
            << rows << " rows, tension " << tension << ", a " << a;
        // Explicit all-ones weights are the same; a reused pyramid and scratch too.
        Signal scratch;
        ReconstructSignal(pyramid, std::vector<double>(pyramid.levels() + 1, 1.0), &out, &scratch);
        EXPECT_LT((out - signal).cwiseAbs().maxCoeff(), 1e-9);
      }
    }
  }
}

TEST(LaplacianPyramid, StraightLineHasNoBandsAndKeepsItsEnds) {
  for (int rows : {9, 10, 57}) {
    Signal line(rows, 2);
    for (int i = 0; i < rows; ++i) line.row(i) << 3.0 - 0.5 * i, 7.0 + 2.0 * i;
    LaplacianPyramid pyramid;
    ASSERT_TRUE(BuildLaplacianPyramid(line, PyramidOptions(), &pyramid).ok());
    for (const Signal& band : pyramid.laplacian) EXPECT_LT(band.cwiseAbs().maxCoeff(), 1e-12);
    Signal smooth;
    ReconstructSignal(pyramid, DropFinestBands(pyramid.levels(), pyramid.levels()), &smooth);
    EXPECT_LT((smooth - line).cwiseAbs().maxCoeff(), 1e-12) << rows;
  }
}

TEST(LaplacianPyramid, BandWeightsAreLinear) {
  const Signal signal = RandomSignal(200, 2, 5);
  PyramidOptions options;
  options.levels = 3;
  LaplacianPyramid pyramid;
  ASSERT_TRUE(BuildLaplacianPyramid(signal, options, &pyramid).ok());
  const std::vector<double> weights = {2.0, 1.5, 0.0, 1.0};  // The paper's example.
  Signal edited, sum = Signal::Zero(200, 2), part;
  ReconstructSignal(pyramid, weights, &edited);
  for (int l = 0; l <= 3; ++l) {
    std::vector<double> one(4, 0.0);
    one[l] = weights[l];
    ReconstructSignal(pyramid, one, &part);
    sum += part;
  }
  EXPECT_LT((edited - sum).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_TRUE(CheckBandWeights(weights, 3, "--weights").ok());
  EXPECT_FALSE(CheckBandWeights({1.0, 1.0}, 3, "--weights").ok());
}

// Energy of each band's full-rate contribution (top Gaussian last).
std::vector<double> BandEnergies(const Signal& signal, int levels) {
  PyramidOptions options;
  options.levels = levels;
  LaplacianPyramid pyramid;
  EXPECT_TRUE(BuildLaplacianPyramid(signal, options, &pyramid).ok());
  std::vector<double> energies;
  Signal part;
  for (int l = 0; l <= levels; ++l) {
    std::vector<double> one(levels + 1, 0.0);
    one[l] = 1.0;
    ReconstructSignal(pyramid, one, &part);
    energies.push_back(part.squaredNorm());
  }
  return energies;
}

TEST(LaplacianPyramid, SinusoidLandsInItsBand) {
  // Band l holds periods of about 3 * 2^l .. 3 * 2^(l+1) frames (level l samples every
  // 2^l frames; REDUCE halves the band); a period of 2^(l+2) frames sits in its middle
  // (measured: 84-100% of the energy in band l, the rest in its neighbours).
  for (int l = 0; l <= 4; ++l) {
    const double period = 4.0 * (1 << l);
    Signal signal(1024, 1);
    for (int i = 0; i < 1024; ++i) signal(i, 0) = std::sin(2.0 * kPi * i / period);
    const std::vector<double> energies = BandEnergies(signal, 6);
    double total = 0.0;
    for (double e : energies) total += e;
    int best = 0;
    for (int k = 1; k < static_cast<int>(energies.size()); ++k) {
      if (energies[k] > energies[best]) best = k;
    }
    EXPECT_EQ(best, l) << "period " << period;
    EXPECT_GT(energies[l] / total, 0.8) << "period " << period;
  }
}

// A pyramid assembled from outside (the Python bands) must have Build's sizes before
// ReconstructSignal runs: a mismatched band corrupted the heap, a wrong top was upsampled.
TEST(LaplacianPyramid, CheckPyramidShapeRejectsEveryMismatch) {
  Signal signal(100, 7);
  for (Eigen::Index i = 0; i < signal.size(); ++i) signal.data()[i] = std::sin(0.1 * static_cast<double>(i));
  PyramidOptions options;
  options.levels = 3;
  LaplacianPyramid good;
  ASSERT_TRUE(BuildLaplacianPyramid(signal, options, &good).ok());
  EXPECT_TRUE(CheckPyramidShape(good).ok());
  auto bad = [&](auto change) {
    LaplacianPyramid p = good;
    change(&p);
    const Status status = CheckPyramidShape(p);
    return !status.ok() && status.message().find('\n') == std::string::npos;
  };
  EXPECT_TRUE(bad([](LaplacianPyramid* p) { p->gaussian.back() = Signal::Zero(25, 7); }));    // Top too long.
  EXPECT_TRUE(bad([](LaplacianPyramid* p) { p->gaussian.back() = Signal::Zero(13, 6); }));    // Channels.
  EXPECT_TRUE(bad([](LaplacianPyramid* p) { p->laplacian[1] = Signal::Zero(49, 7); }));       // A band.
  EXPECT_TRUE(bad([](LaplacianPyramid* p) { p->laplacian[0] = Signal::Zero(2, 7); }));        // Too short.
  EXPECT_TRUE(bad([](LaplacianPyramid* p) { p->laplacian.clear(); }));                        // No band.
  EXPECT_TRUE(bad([](LaplacianPyramid* p) { p->gaussian.clear(); }));                         // No top.
  EXPECT_TRUE(bad([](LaplacianPyramid* p) { p->laplacian[2](0, 0) = std::nan(""); }));       // NaN.
  EXPECT_TRUE(bad([](LaplacianPyramid* p) {                                                  // Too many.
    p->laplacian.assign(8, Signal::Zero(5, 7));
  }));
}

}  // namespace
}  // namespace mocapsolve
