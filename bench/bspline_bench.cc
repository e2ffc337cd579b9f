// B-spline benchmarks on the workloads of docs/benchmarks.md.
//
//   build/release/bench/bspline_bench --benchmark_min_time=1
//
// W1: cubic clamped B-spline, 100 control points from LCG seed 1, clamped
// uniform knots; positions at N = 10^6 parameters t_k = k / (N - 1), single
// thread. W2: the W1 curve, position and first derivative. W7 (curves): W1
// on every pool thread. Plus the W1 curve as a NURBS (weights from seed 5 in
// [0.5, 1.5]) and a degree sweep, for context.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <thread>
#include <vector>

#include "freeform/core/bspline.h"
#include "freeform/core/thread_pool.h"
#include "workloads.h"

namespace {

using freeform::bench::ClampedUniformKnots;
using freeform::bench::RandomPoints;
using freeform::bench::UniformParameters;

struct Workload {
  int degree = 3;
  int control_points = 100;
  size_t parameters = 1'000'000;
  int orders = 1;
  bool rational = false;
  freeform::ThreadPool* pool = nullptr;
};

void RunBSpline(benchmark::State& state, const Workload& workload) {
  const std::vector<double> control = RandomPoints(
      1, static_cast<size_t>(workload.control_points), /*dimension=*/3);
  const std::vector<double> knots =
      ClampedUniformKnots(workload.control_points, workload.degree);
  std::vector<double> weights;
  if (workload.rational) {
    weights = RandomPoints(5, static_cast<size_t>(workload.control_points), 1);
    for (double& weight : weights) weight = 1.0 + 0.5 * weight;
  }
  const std::vector<double> parameters = UniformParameters(workload.parameters);
  std::vector<std::vector<double>> buffers(
      static_cast<size_t>(workload.orders),
      std::vector<double>(workload.parameters * 3));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  const freeform::BSplineCurveView curve{
      .degree = workload.degree,
      .control_points = {.dimension = 3, .coordinates = control},
      .knots = knots,
      .weights = weights};
  const freeform::ExecutionContext context{.pool = workload.pool};
  for (auto _ : state) {
    const absl::Status status =
        freeform::EvaluateBSplineCurve(curve, parameters, output, context);
    if (!status.ok()) {
      state.SkipWithError(status.ToString().c_str());
      return;
    }
    benchmark::ClobberMemory();
  }
  double checksum = 0;
  for (const auto& buffer : buffers) {
    for (double value : buffer) checksum += value;
  }
  state.counters["checksum"] = checksum;
  state.counters["points/s"] =
      benchmark::Counter(static_cast<double>(workload.parameters) *
                             static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
}

void BM_W1_CubicBSplinePositions(benchmark::State& state) {
  RunBSpline(state, {});
}
BENCHMARK(BM_W1_CubicBSplinePositions)->Unit(benchmark::kMillisecond);

void BM_W2_CubicBSplineFirstDerivative(benchmark::State& state) {
  RunBSpline(state, {.orders = 2});
}
BENCHMARK(BM_W2_CubicBSplineFirstDerivative)->Unit(benchmark::kMillisecond);

void BM_W7_CubicBSplinePositionsAllThreads(benchmark::State& state) {
  freeform::ThreadPool pool(
      static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  RunBSpline(state, {.pool = &pool});
}
BENCHMARK(BM_W7_CubicBSplinePositionsAllThreads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// W1 and W7 on a batch of 2^16 parameters, whose 2 MB of parameters and
// points stay in the caches: how two threads scale when main memory's
// bandwidth is out of the way (docs/performance_profile.md, W7).
constexpr size_t kCachedBatch = size_t{1} << 16;

void BM_W1_CachedBatch(benchmark::State& state) {
  RunBSpline(state, {.parameters = kCachedBatch});
}
BENCHMARK(BM_W1_CachedBatch)->Unit(benchmark::kMicrosecond)->UseRealTime();

void BM_W7_CachedBatchAllThreads(benchmark::State& state) {
  freeform::ThreadPool pool(
      static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  RunBSpline(state, {.parameters = kCachedBatch, .pool = &pool});
}
BENCHMARK(BM_W7_CachedBatchAllThreads)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

void BM_CubicNurbs(benchmark::State& state) {
  RunBSpline(state,
             {.orders = static_cast<int>(state.range(0)), .rational = true});
}
BENCHMARK(BM_CubicNurbs)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// Degrees beyond the compiled-in kernels (0..5) use the generic one.
void BM_BSplineDegree(benchmark::State& state) {
  RunBSpline(state, {.degree = static_cast<int>(state.range(0)),
                     .parameters = 100'000,
                     .orders = static_cast<int>(state.range(1))});
}
BENCHMARK(BM_BSplineDegree)
    ->ArgsProduct({{1, 2, 5, 7, 15}, {1, 2}})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
