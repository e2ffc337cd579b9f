// Surface benchmarks on the workloads of docs/benchmarks.md.
//
//   build/release/bench/surface_bench --benchmark_min_time=1
//
// W3: bicubic clamped B-spline surface, 20 x 20 control points from LCG
// seed 2 (row-major P[i][j], i along u), clamped uniform knots both ways;
// positions on a 1000 x 1000 grid of (u_i, v_j), single thread. W7
// (surfaces): the same on every pool thread. Plus positions with first
// partials and normals, the cost a renderer pays.
#include <benchmark/benchmark.h>

#include <thread>
#include <vector>

#include "freeform/core/normals.h"
#include "freeform/core/tensor_surface.h"
#include "freeform/core/thread_pool.h"
#include "workloads.h"

namespace {

using freeform::bench::ClampedUniformKnots;
using freeform::bench::RandomPoints;
using freeform::bench::UniformParameters;

void RunW3(benchmark::State& state, int max_order, bool normals,
           freeform::ThreadPool* pool) {
  const std::vector<double> net = RandomPoints(2, 20 * 20, 3);
  const std::vector<double> knots = ClampedUniformKnots(20, 3);
  const std::vector<double> grid = UniformParameters(1000);
  const freeform::BSplineSurfaceView surface{
      .degree_u = 3,
      .degree_v = 3,
      .control_net = {.dimension = 3,
                      .count_u = 20,
                      .count_v = 20,
                      .coordinates = net},
      .knots_u = knots,
      .knots_v = knots,
      .weights = {}};
  const size_t count = grid.size() * grid.size();
  std::vector<std::vector<double>> buffers(freeform::PartialCount(max_order),
                                           std::vector<double>(3 * count));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  std::vector<double> unit_normals(normals ? 3 * count : 0);
  const auto samples = freeform::SurfaceSamples::Grid(grid, grid);
  const freeform::ExecutionContext context{.pool = pool};
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        freeform::EvaluateBSplineSurface(surface, samples, output, context));
    if (normals) {
      benchmark::DoNotOptimize(freeform::ComputeUnitNormals(
          output, samples, freeform::BSplineSurfaceDomain(surface),
          absl::MakeSpan(unit_normals)));
    }
    benchmark::ClobberMemory();
  }
  double checksum = 0;
  for (double value : buffers[0]) checksum += value;
  state.counters["checksum"] = checksum;
  state.counters["points/s"] = benchmark::Counter(
      static_cast<double>(count) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}

void BM_W3_BicubicSurfaceGrid(benchmark::State& state) {
  RunW3(state, 0, false, nullptr);
}
BENCHMARK(BM_W3_BicubicSurfaceGrid)->Unit(benchmark::kMillisecond);

void BM_W7_BicubicSurfaceGridAllThreads(benchmark::State& state) {
  freeform::ThreadPool pool(
      static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  RunW3(state, 0, false, &pool);
}
BENCHMARK(BM_W7_BicubicSurfaceGridAllThreads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_W3_WithPartialsAndNormals(benchmark::State& state) {
  RunW3(state, 2, true, nullptr);
}
BENCHMARK(BM_W3_WithPartialsAndNormals)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
