// Constrained Delaunay triangulation benchmarks:
//
//   build/release/bench/triangulation_bench --benchmark_min_time=1
//
// T1: 10^4, 10^5 and 10^6 points uniform in the unit square (LCG seed 1),
// Delaunay only. T2: a loop of 10^5 segments (a regular 10^5-gon of radius
// 1), with the region inside it.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "freeform/core/constrained_delaunay.h"

namespace {

using freeform::ConstrainedTriangulationOptions;
using freeform::Point2;

std::vector<Point2> UniformPoints(int64_t count) {
  uint64_t state = 1;
  const auto next = [&state] {
    state = state * 6364136223846793005u + 1442695040888963407u;
    return static_cast<double>(state >> 11) * 0x1p-53;
  };
  std::vector<Point2> points(static_cast<size_t>(count));
  for (Point2& p : points) p = {next(), next()};
  return points;
}

void Triangulate(benchmark::State& state, const std::vector<Point2>& points,
                 const std::vector<std::array<int32_t, 2>>& segments,
                 ConstrainedTriangulationOptions options) {
  size_t triangles = 0;
  for (auto _ : state) {
    auto result =
        freeform::TriangulateConstrained(points, segments, options, nullptr);
    if (!result.ok()) {
      state.SkipWithError("triangulation failed");
      return;
    }
    triangles = result->triangles.size();
    benchmark::DoNotOptimize(result);
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["points_per_second"] =
      benchmark::Counter(static_cast<double>(points.size()),
                         benchmark::Counter::kIsIterationInvariantRate);
}

void BM_DelaunayUniform(benchmark::State& state) {
  Triangulate(state, UniformPoints(state.range(0)), {}, {});
}
BENCHMARK(BM_DelaunayUniform)
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);

void BM_ConstrainedLoop(benchmark::State& state) {
  const auto count = static_cast<int32_t>(state.range(0));
  std::vector<Point2> points;
  std::vector<std::array<int32_t, 2>> segments;
  for (int32_t i = 0; i < count; ++i) {
    const double angle = 2 * std::numbers::pi * i / count;
    points.push_back({std::cos(angle), std::sin(angle)});
    segments.push_back({i, (i + 1) % count});
  }
  Triangulate(state, points, segments,
              {ConstrainedTriangulationOptions::Region::kInsideSegments});
}
BENCHMARK(BM_ConstrainedLoop)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
