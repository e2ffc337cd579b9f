// Core benchmarks on the workloads of docs/benchmarks.md.
//
//   build/release/bench/core_bench --benchmark_min_time=1
//
// W4: cubic Bezier, 4 control points from LCG seed 3, positions at 10^7
// parameters t_k = k / (N - 1), single thread; plus the same batch on every
// pool thread (the W7 idea applied to Bezier) and higher degrees.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <thread>
#include <vector>

#include "freeform/core/bezier.h"
#include "freeform/core/thread_pool.h"
#include "workloads.h"

namespace {

using freeform::bench::RandomPoints;
using freeform::bench::UniformParameters;

void RunBezier(
    benchmark::State& state, int degree, size_t count, int orders,
    freeform::ThreadPool* pool,
    freeform::BezierAlgorithm algorithm = freeform::BezierAlgorithm::kAuto) {
  const std::vector<double> control =
      RandomPoints(3, static_cast<size_t>(degree + 1), 3);
  const std::vector<double> parameters = UniformParameters(count);
  std::vector<std::vector<double>> buffers(static_cast<size_t>(orders),
                                           std::vector<double>(count * 3));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  const freeform::BezierCurveView curve{
      .control_points = {.dimension = 3, .coordinates = control},
      .weights = {}};
  const freeform::ExecutionContext context{.pool = pool};
  // One untimed call first: the 320 MB of parameters and output were last
  // touched by their setup, and on a virtual machine whose kernel reclaims
  // idle pages (DAMON) the first calls would time re-faulting them.
  benchmark::DoNotOptimize(freeform::EvaluateBezierCurve(
      curve, parameters, output, context, algorithm));
  for (auto _ : state) {
    benchmark::DoNotOptimize(freeform::EvaluateBezierCurve(
        curve, parameters, output, context, algorithm));
    benchmark::ClobberMemory();
  }
  double checksum = 0;
  for (const auto& buffer : buffers) {
    for (double value : buffer) checksum += value;
  }
  state.counters["checksum"] = checksum;
  state.counters["points/s"] = benchmark::Counter(
      static_cast<double>(count) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}

void BM_W4_CubicBezierPositions(benchmark::State& state) {
  RunBezier(state, 3, 10'000'000, 1, nullptr);
}
BENCHMARK(BM_W4_CubicBezierPositions)->Unit(benchmark::kMillisecond);

void BM_W4_CubicBezierPositionsAllThreads(benchmark::State& state) {
  freeform::ThreadPool pool(
      static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  RunBezier(state, 3, 10'000'000, 1, &pool);
}
BENCHMARK(BM_W4_CubicBezierPositionsAllThreads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Arguments: degree, derivative orders (1 = positions), algorithm
// (1 de Casteljau, 2 Horner, 3 ladder).
void BM_BezierDegree(benchmark::State& state) {
  RunBezier(state, static_cast<int>(state.range(0)), 100'000,
            static_cast<int>(state.range(1)), nullptr,
            static_cast<freeform::BezierAlgorithm>(state.range(2)));
}
BENCHMARK(BM_BezierDegree)
    ->ArgsProduct({{3, 7, 15, 30}, {1, 2}, {1, 2, 3}})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
