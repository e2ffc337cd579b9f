// Benchmarks of the operations that build geometry, on the workloads of
// docs/benchmarks.md.
//
//   build/release/bench/construction_bench --benchmark_min_time=1
//
// W5: global cubic B-spline interpolation, chord-length parameters,
// averaging knots, of N = 10^5 points P_i = (10 cos(0.01 i) + 0.1 r1,
// 10 sin(0.01 i) + 0.1 r2, 0.01 i + 0.1 r3), r drawn from LCG seed 4 (also
// 10^4 and 10^6 to show linear growth). W6: degree elevation by 1 of the W1
// curve (result: 197 control points), and by 2 and 3.
#include <benchmark/benchmark.h>

#include <vector>

#include "core_workloads.h"
#include "freeform/core/elevation.h"
#include "freeform/core/interpolation.h"
#include "workloads.h"

namespace {

using freeform::bench::W5Points;

void BM_W5_GlobalCubicInterpolation(benchmark::State& state) {
  const std::vector<double> points =
      W5Points(static_cast<size_t>(state.range(0)));
  freeform::CurveInterpolationOptions options;
  options.degree = 3;
  double checksum = 0;
  for (auto _ : state) {
    auto result = freeform::InterpolateCurve({3, points}, options);
    if (!result.ok()) state.SkipWithError("interpolation failed");
    checksum = 0;
    for (double value : result->curve.coordinates) checksum += value;
    benchmark::DoNotOptimize(checksum);
  }
  state.counters["checksum"] = checksum;
}
BENCHMARK(BM_W5_GlobalCubicInterpolation)
    ->Arg(10'000)
    ->Arg(100'000)
    ->Arg(1'000'000)
    ->Unit(benchmark::kMillisecond);

// ElevateW1 raises the W1 curve by `by` every iteration. The checksum is
// the sum of the elevated control points' coordinates (OpenCASCADE's W6
// figure reports the same sum).
void ElevateW1(benchmark::State& state, int by) {
  const freeform::BSplineCurveData curve = freeform::bench::W1Curve();
  absl::StatusOr<freeform::BSplineCurveData> elevated;
  for (auto _ : state) {
    elevated = freeform::ElevateBSplineCurve(curve.view(), by);
    benchmark::DoNotOptimize(elevated);
  }
  if (!elevated.ok()) {
    state.SkipWithError("elevation failed");
    return;
  }
  double checksum = 0;
  for (const double value : elevated->coordinates) checksum += value;
  state.counters["checksum"] = checksum;
  state.counters["control_points"] =
      static_cast<double>(elevated->coordinates.size() / 3);
}

void BM_W6_ElevateW1ByOne(benchmark::State& state) { ElevateW1(state, 1); }
BENCHMARK(BM_W6_ElevateW1ByOne)->Unit(benchmark::kMicrosecond);

// The W6 curve raised by 2 and 3, where each control point averages over
// subsets of its arguments instead of leaving one out.
void BM_ElevateW1By(benchmark::State& state) {
  ElevateW1(state, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_ElevateW1By)->Arg(2)->Arg(3)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
