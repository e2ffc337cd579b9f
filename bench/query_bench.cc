// Geometric query benchmarks (issue #12) on the workloads of
// docs/benchmarks.md; bench/peers/occt_query_bench.cc runs the same
// workloads with OpenCASCADE.
//
//   build/release/bench/query_bench --benchmark_min_time=1
//
// Q1: closest points on the W1 curve (cubic clamped B-spline, 100 control
// points from LCG seed 1, 3D) of 10^5 query points from LCG seed 11,
// uniform in the control points' bounding box inflated by 10% about its
// centre; single thread, default options (tolerance 1e-9). Checksum: the
// sum of the distances.
// Q2: intersections of two planar cubic clamped B-splines of 100 control
// points each from LCG seeds 1 and 2 (in [-1, 1)^2; they cross 935 times,
// as many as the proper crossings of the two curves sampled at 2 * 10^5
// parameters each); default options. Checksums: the number of points and
// the sum of both parameters over them.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

#include "absl/strings/str_format.h"
#include "freeform/core/closest_point.h"
#include "freeform/core/curve.h"
#include "freeform/core/intersection.h"
#include "workloads.h"

namespace {

using freeform::bench::PointsInBox;
using freeform::bench::RandomSpline;
using freeform::bench::SplineData;

constexpr size_t kQueries = 100'000;

freeform::Curve CurveOf(const SplineData& data) {
  return *freeform::BSplineCurve::Create(
      {.degree = data.degree,
       .control_points = {.dimension = data.dimension,
                          .coordinates = data.points},
       .knots = data.knots,
       .weights = {}});
}

void BM_Q1_ClosestPointsOnW1(benchmark::State& state) {
  const SplineData data = RandomSpline(1, 100, 3);
  const freeform::Curve curve = CurveOf(data);
  const std::vector<double> queries =
      PointsInBox(data.points, 3, 1.1, 11, kQueries);
  double checksum = 0.0;
  for (auto _ : state) {
    const absl::StatusOr<freeform::ClosestPoints> answer =
        freeform::CurveClosestPoints(curve, {3, queries});
    if (!answer.ok()) {
      state.SkipWithError(answer.status().ToString().c_str());
      return;
    }
    checksum = 0.0;
    for (const double distance : answer->distances) checksum += distance;
    benchmark::DoNotOptimize(checksum);
  }
  state.SetLabel(absl::StrFormat("sum of distances %.6f", checksum));
  state.counters["queries/s"] = benchmark::Counter(
      static_cast<double>(kQueries) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Q1_ClosestPointsOnW1)->Unit(benchmark::kMillisecond);

void BM_Q2_IntersectTwoPlanarSplines(benchmark::State& state) {
  const SplineData first_data = RandomSpline(1, 100, 2);
  const SplineData second_data = RandomSpline(2, 100, 2);
  const freeform::Curve first = CurveOf(first_data);
  const freeform::Curve second = CurveOf(second_data);
  size_t points = 0;
  double parameters = 0.0;
  for (auto _ : state) {
    const absl::StatusOr<freeform::CurveIntersections> answer =
        freeform::IntersectCurves(first, second);
    if (!answer.ok()) {
      state.SkipWithError(answer.status().ToString().c_str());
      return;
    }
    points = answer->first_parameters.size();
    parameters = 0.0;
    for (size_t k = 0; k < points; ++k) {
      parameters += answer->first_parameters[k] + answer->second_parameters[k];
    }
    benchmark::DoNotOptimize(parameters);
  }
  state.SetLabel(
      absl::StrFormat("%zu points, parameter sum %.6f", points, parameters));
}
BENCHMARK(BM_Q2_IntersectTwoPlanarSplines)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
