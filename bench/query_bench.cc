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
// Q3: the Bezier curve of degree n with control points (i / n, 1/2,
// (-1)^i), i = 0..n, that is (t, 1/2, (1 - 2t)^n), against the unit square
// of z = 0 at tolerance 1e-9: it touches the square to order n, one overlap
// over |1 - 2t| <= 1e-9^(1/n). Checksum: the overlap's length.
// Q4: a search that spends the whole default work budget (max_work 2^28):
// two planar cubic clamped B-splines of 2000 control points from LCG seeds
// 1 and 2, until RESOURCE_EXHAUSTED.
// Q5: the section z = 1 of the sphere patch of radius 2 at tolerance 1e-12
// under the server's default cap of 65536 vertices, until
// RESOURCE_EXHAUSTED; and at 1e-8 (16,385 vertices), answered.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "absl/strings/str_format.h"
#include "freeform/core/bezier.h"
#include "freeform/core/closest_point.h"
#include "freeform/core/curve.h"
#include "freeform/core/intersection.h"
#include "freeform/core/section.h"
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

void BM_Q3_HighOrderContactWithASquare(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::vector<double> zigzag;
  for (int i = 0; i <= n; ++i) {
    zigzag.insert(zigzag.end(),
                  {static_cast<double>(i) / n, 0.5, i % 2 == 0 ? 1.0 : -1.0});
  }
  const freeform::Curve curve =
      *freeform::BezierCurve::Create({{3, zigzag}, {}});
  const std::vector<double> net = {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0};
  const freeform::Surface square =
      *freeform::BezierSurface::Create({{3, 2, 2, net}, {}});
  double length = 0.0;
  for (auto _ : state) {
    const absl::StatusOr<freeform::CurveSurfaceIntersections> answer =
        freeform::IntersectCurveSurface(curve, square);
    if (!answer.ok() || answer->curve_intervals.size() != 2) {
      state.SkipWithError(answer.status().ToString().c_str());
      return;
    }
    length = answer->curve_intervals[1] - answer->curve_intervals[0];
    benchmark::DoNotOptimize(length);
  }
  state.SetLabel(absl::StrFormat("overlap of length %.9f (exact %.9f)", length,
                                 std::pow(1e-9, 1.0 / n)));
}
BENCHMARK(BM_Q3_HighOrderContactWithASquare)
    ->Arg(16)
    ->Arg(48)
    ->Arg(64)
    ->Unit(benchmark::kMillisecond);

void BM_Q4_IntersectionSpendsItsWorkBudget(benchmark::State& state) {
  const SplineData first_data = RandomSpline(1, 2000, 2);
  const SplineData second_data = RandomSpline(2, 2000, 2);
  const freeform::Curve first = CurveOf(first_data);
  const freeform::Curve second = CurveOf(second_data);
  for (auto _ : state) {
    const absl::Status status =
        freeform::IntersectCurves(first, second, {.max_results = 1 << 16})
            .status();
    if (status.code() != absl::StatusCode::kResourceExhausted) {
      state.SkipWithError(status.ToString().c_str());
      return;
    }
  }
}
BENCHMARK(BM_Q4_IntersectionSpendsItsWorkBudget)->Unit(benchmark::kMillisecond);

void BM_Q5_SphereSection(benchmark::State& state) {
  const double tolerance = state.range(0) == 12 ? 1e-12 : 1e-8;
  // The octant of the sphere of radius 2 as a rational biquadratic patch
  // (tests/core/shapes.h, SpherePatch).
  const double w = std::sqrt(0.5);
  const double r = 2.0;
  std::vector<double> net, weights;
  const double profile[3][3] = {{r, 0, 1}, {r, r, w}, {0, r, 1}};
  const double turn[3][3] = {{1, 0, 1}, {1, 1, w}, {0, 1, 1}};
  for (const auto& p : profile) {
    for (const auto& c : turn) {
      net.insert(net.end(), {p[0] * c[0], p[0] * c[1], p[1]});
      weights.push_back(p[2] * c[2]);
    }
  }
  const freeform::Surface sphere =
      *freeform::BezierSurface::Create({{3, 3, 3, net}, weights});
  const std::vector<double> point = {0, 0, 1};
  const std::vector<double> up = {0, 0, 1};
  size_t vertices = 0;
  for (auto _ : state) {
    const absl::StatusOr<freeform::Sections> answer =
        freeform::IntersectSurfacePlane(
            sphere, point, up, {.tolerance = tolerance, .max_points = 65536});
    if (answer.ok() == (tolerance < 1e-10)) {
      state.SkipWithError(answer.status().ToString().c_str());
      return;
    }
    vertices = answer.ok() ? answer->points.size() / 3 : 0;
    benchmark::DoNotOptimize(vertices);
  }
  state.SetLabel(absl::StrFormat("%zu vertices", vertices));
}
BENCHMARK(BM_Q5_SphereSection)->Arg(12)->Arg(8)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
