// The whole-clip DLS's linear algebra at the structure's limit (Google Benchmark):
// BlockBandedCholesky::Factorize on a block-banded SPD matrix shaped like a clip's normal
// equations (n unknowns per frame, bandwidth 1 = velocity, 2 = acceleration smoothness),
// 200 frames. Counters: gflop_per_s (FactorizationFlops over CPU time) and us_per_frame;
// the clip's limit is its FactorizationFlops per iteration at that rate.
//   build/bin/mocapsolve_bench --benchmark_filter=BlockBanded
#include <random>

#include <benchmark/benchmark.h>

#include "solvers/block_banded_cholesky.h"

namespace mocapsolve {
namespace {

void BM_BlockBandedCholesky(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int bandwidth = static_cast<int>(state.range(1));
  const int blocks = 200;
  BlockBandedCholesky reference;
  reference.Resize(blocks, n, bandwidth);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (size_t i = 0; i < reference.size(); ++i) reference.data()[i] = uniform(rng);
  for (int k = 0; k < blocks; ++k) {
    double* diagonal = reference.Block(k, 0);
    for (int i = 0; i < n; ++i) diagonal[i * n + i] += 2.0 * n * (2 * bandwidth + 1);  // SPD.
  }
  BlockBandedCholesky work = reference;
  for (auto _ : state) {
    state.PauseTiming();
    work = reference;
    state.ResumeTiming();
    benchmark::DoNotOptimize(work.Factorize());
  }
  state.counters["gflop_per_s"] = benchmark::Counter(1e-9 * reference.FactorizationFlops(),
                                                     benchmark::Counter::kIsIterationInvariantRate);
  state.counters["us_per_frame"] = benchmark::Counter(1e-6 * blocks, benchmark::Counter::kIsIterationInvariantRate |
                                                                        benchmark::Counter::kInvert);
}
// n = 96: CMU 01_01 with free joints (31 x 3 + 3); n = 58: 02_01's ASF dofs and root.
BENCHMARK(BM_BlockBandedCholesky)->Args({96, 1})->Args({96, 2})->Args({58, 1})->ArgNames({"block", "bandwidth"})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mocapsolve
