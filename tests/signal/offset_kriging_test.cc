// The kriging refill (signal/offset_kriging.h): the offset process recovered from a
// simulated one; white-noise offsets filled with their mean (where the edge blend carries
// an edge sample's noise into the gap); a slow offset kept; a constant offset exact; a
// correlated offset met at the edges; gaps at the ends decaying toward the mean; errors.
#include "signal/offset_kriging.h"

#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

// One marker on a curve; the original is the reference plus offset(f) (f = frame).
void MakePaths(int frames, const std::function<Eigen::Vector3d(int)>& offset, MarkerTrajectories* original,
               MarkerTrajectories* reference) {
  *original = MarkerTrajectories({"M"}, frames);
  *reference = MarkerTrajectories({"M"}, frames);
  for (int f = 0; f < frames; ++f) {
    const Eigen::Vector3d r(std::sin(0.1 * f), 0.002 * f * f, std::cos(0.07 * f));
    reference->SetSample(f, 0, r);
    original->SetSample(f, 0, r + offset(f));
  }
}

// A sampled Ornstein-Uhlenbeck process (stationary from frame 0) of standard deviation
// sigma and time constant tau frames, plus white noise of standard deviation noise, per axis.
std::vector<Eigen::Vector3d> OuSamples(int frames, double sigma, double tau, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  const double rho = std::exp(-1.0 / tau), step = sigma * std::sqrt(1.0 - rho * rho);
  std::vector<Eigen::Vector3d> d(frames);
  Eigen::Vector3d g(sigma * normal(rng), sigma * normal(rng), sigma * normal(rng));
  for (int f = 0; f < frames; ++f) {
    if (f > 0) {
      for (int a = 0; a < 3; ++a) g[a] = rho * g[a] + step * normal(rng);
    }
    d[f] = g + noise * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  }
  return d;
}

// Fills frames [first, last] of the marker by kriging with the process estimated from the
// rest; returns the filled paths.
MarkerTrajectories KrigingFill(const MarkerTrajectories& original, const MarkerTrajectories& reference, int first,
                               int last, OffsetProcess* process = nullptr, int samples_per_side = 10) {
  MarkerTrajectories damaged = original;
  for (int f = first; f <= last; ++f) damaged.SetMissing(f, 0);
  OffsetKrigingOptions options;
  options.samples_per_side = samples_per_side;
  std::vector<OffsetProcess> processes;
  EXPECT_TRUE(EstimateOffsetProcesses(damaged, reference, options, &processes).ok());
  EXPECT_TRUE(processes[0].valid);
  if (process != nullptr) *process = processes[0];
  const MarkerTrajectories observed = damaged;
  EXPECT_TRUE(FillGapByKriging(FindGaps(damaged)[0], observed, reference, processes[0], options, &damaged).ok());
  return damaged;
}

double WorstError(const MarkerTrajectories& a, const MarkerTrajectories& b, int first, int last) {
  double worst = 0.0;
  for (int f = first; f <= last; ++f) worst = std::max(worst, (a.position(f, 0) - b.position(f, 0)).norm());
  return worst;
}

TEST(OffsetKriging, RecoversTheProcessOfASimulatedOffset) {
  // 6,000 frames of OU (sigma 2, tau 25 frames) plus white noise 0.5: the variogram fit
  // should find each within the sampling error of one take (tau to a factor 1.5, the
  // variances to 35 %).
  const std::vector<Eigen::Vector3d> d = OuSamples(6000, 2.0, 25.0, 0.5, 7);
  MarkerTrajectories original, reference;
  MakePaths(6000, [&](int f) { return Eigen::Vector3d(d[f] + Eigen::Vector3d(1.0, -2.0, 0.5)); }, &original,
            &reference);
  std::vector<OffsetProcess> processes;
  ASSERT_TRUE(EstimateOffsetProcesses(original, reference, OffsetKrigingOptions(), &processes).ok());
  ASSERT_EQ(processes.size(), 1u);
  const OffsetProcess& p = processes[0];
  ASSERT_TRUE(p.valid);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(p.mean[a], Eigen::Vector3d(1.0, -2.0, 0.5)[a], 0.5) << a;
    EXPECT_GT(p.time_constant[a], 25.0 / 1.5) << a;
    EXPECT_LT(p.time_constant[a], 25.0 * 1.5) << a;
    EXPECT_NEAR(p.process_variance[a], 4.0, 0.35 * 4.0) << a;
    EXPECT_NEAR(p.noise_variance[a], 0.25, 0.35 * 0.25) << a;
  }
}

TEST(OffsetKriging, WhiteNoiseOffsetIsFilledWithItsMean) {
  // The offset is a constant plus white noise (sd 1 per axis): the best fill is the
  // reference plus the constant. The edge blend joins the two edge samples and carries
  // their noise (up to ~3 per axis) into the gap; kriging averages it away.
  const Eigen::Vector3d mean(0.5, -1.0, 2.0);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> noise(600);
  for (auto& n : noise) n = Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  MarkerTrajectories original, reference, truth;
  MakePaths(600, [&](int f) { return Eigen::Vector3d(mean + noise[f]); }, &original, &reference);
  MakePaths(600, [&](int) { return mean; }, &truth, &reference);
  const int first = 250, last = 299;
  OffsetProcess process;
  const MarkerTrajectories kriged = KrigingFill(original, reference, first, last, &process);
  EXPECT_LT(process.process_variance.maxCoeff(), 0.2);  // Little correlated part found.
  EXPECT_NEAR(process.noise_variance.mean(), 1.0, 0.3);
  // The mean is estimated from 550 samples (median: sd ~ 1.25 / sqrt(550) per axis) and
  // the remaining process part is small.
  EXPECT_LT(WorstError(kriged, truth, first, last), 0.35);
  MarkerTrajectories blended = original;
  for (int f = first; f <= last; ++f) blended.SetMissing(f, 0);
  ASSERT_TRUE(FillGapFromReference(FindGaps(blended)[0], reference, GapFillOptions(), &blended).ok());
  EXPECT_GT(WorstError(blended, truth, first, last), 3.0 * WorstError(kriged, truth, first, last));
}

TEST(OffsetKriging, SlowOffsetIsKept) {
  // A slow, smooth offset (soft tissue: 3 units over 100-frame swings, no noise): the fill
  // follows the edges and stays within a small part of the offset's change over the gap,
  // far from the mean.
  MarkerTrajectories original, reference;
  MakePaths(900, [](int f) { return Eigen::Vector3d(3.0 * std::sin(f / 100.0), 0.01 * f, -1.0); }, &original,
            &reference);
  const int first = 400, last = 429;
  const MarkerTrajectories kriged = KrigingFill(original, reference, first, last);
  // Over the gap x moves by ~0.9 and y by 0.3; the fill stays within 0.1 of the truth.
  EXPECT_LT(WorstError(kriged, original, first, last), 0.1);
}

TEST(OffsetKriging, ConstantOffsetIsExact) {
  MarkerTrajectories original, reference;
  MakePaths(200, [](int) { return Eigen::Vector3d(1.0, 2.0, -3.0); }, &original, &reference);
  // In the middle, at the start, at the end.
  for (auto [first, last] : std::vector<std::pair<int, int>>{{80, 119}, {0, 9}, {190, 199}}) {
    const MarkerTrajectories kriged = KrigingFill(original, reference, first, last);
    EXPECT_LT(WorstError(kriged, original, first, last), 1e-12) << first;
  }
}

TEST(OffsetKriging, CorrelatedOffsetIsMetAtTheEdges) {
  // A noise-free OU offset (sd 2, tau 50 frames): the fill starts and ends within a
  // frame's step of the edge samples (continuous for an animator), and ends of the take
  // decay toward the mean from the one edge.
  const std::vector<Eigen::Vector3d> d = OuSamples(3000, 2.0, 50.0, 0.0, 11);
  MarkerTrajectories original, reference;
  MakePaths(3000, [&](int f) { return d[f]; }, &original, &reference);
  const int first = 1500, last = 1519;
  const MarkerTrajectories kriged = KrigingFill(original, reference, first, last);
  auto offset = [&](const MarkerTrajectories& x, int f) {
    return Eigen::Vector3d(x.position(f, 0) - reference.position(f, 0));
  };
  // A frame's move of the offset: sd 2 sqrt(2 / 50) = 0.4 per axis; 3 of it over 3 axes.
  const double step = 3.0 * 0.4 * std::sqrt(3.0);
  EXPECT_LT((offset(kriged, first) - offset(original, first - 1)).norm(), step);
  EXPECT_LT((offset(kriged, last) - offset(original, last + 1)).norm(), step);
  // The gap of 20 frames at tau 50: the conditional sd in its middle is ~0.9 per axis
  // (against the process' 2), so the worst of 20 frames stays under ~2 sd over 3 axes.
  EXPECT_LT(WorstError(kriged, original, first, last), 3.2);
  // A gap running to the end: near the edge the fill is the edge's offset, 400 frames (8
  // tau) on it is the mean (median of the offsets).
  OffsetProcess process;
  const MarkerTrajectories tail = KrigingFill(original, reference, 2500, 2999, &process);
  EXPECT_LT((offset(tail, 2500) - offset(original, 2499)).norm(), step);
  EXPECT_LT((offset(tail, 2900) - process.mean).norm(), 0.05);
}

TEST(OffsetKriging, ErrorsOnMismatchMissingReferenceOrNoProcess) {
  MarkerTrajectories original, reference;
  MakePaths(100, [](int) { return Eigen::Vector3d::Zero(); }, &original, &reference);
  MarkerTrajectories damaged = original;
  damaged.SetMissing(50, 0);
  const Gap gap = FindGaps(damaged)[0];
  std::vector<OffsetProcess> processes;
  MarkerTrajectories short_reference({"M"}, 10);
  EXPECT_FALSE(EstimateOffsetProcesses(damaged, short_reference, OffsetKrigingOptions(), &processes).ok());
  ASSERT_TRUE(EstimateOffsetProcesses(damaged, reference, OffsetKrigingOptions(), &processes).ok());
  const MarkerTrajectories observed = damaged;
  EXPECT_FALSE(FillGapByKriging(gap, observed, short_reference, processes[0], OffsetKrigingOptions(), &damaged).ok());
  reference.SetMissing(50, 0);
  const Status status = FillGapByKriging(gap, observed, reference, processes[0], OffsetKrigingOptions(), &damaged);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("frame 50"), std::string::npos) << status.message();
  // Too few samples to estimate a process (the options ask for 60; 5 valid).
  MarkerTrajectories sparse({"M"}, 100);
  for (int f = 0; f < 5; ++f) sparse.SetSample(f, 0, Eigen::Vector3d::Zero());
  ASSERT_TRUE(EstimateOffsetProcesses(sparse, original, OffsetKrigingOptions(), &processes).ok());
  EXPECT_FALSE(processes[0].valid);
  EXPECT_FALSE(FillGapByKriging(FindGaps(sparse)[0], sparse, original, processes[0], OffsetKrigingOptions(), &sparse).ok());
}

}  // namespace
}  // namespace mocapsolve
