// Benchmarks of the core operations that no peer figure covers (issue #14):
//
//   build/release/bench/operations_bench --benchmark_min_time=1
//
// Teapot: the Utah teapot of examples/teapot.json (32 bicubic Bezier
// patches) meshed within 1e-3 and 1e-4 (TessellateSurfaces: PlanMesh and
// TessellatePlanned); counters: vertices and triangles.
// Knot insertion into the W1 curve (cubic clamped B-spline, 100 control
// points from LCG seed 1): one knot at 0.37, and a refinement by 1,000 knots
// (k + 1/2) / 1000, k = 0..999 (none equals a knot i / 97 of W1).
// Decompose: the W1 curve into its 97 Bezier segments, the W3 surface
// (bicubic, 20 x 20 control points from seed 2) into its 17 x 17 patches.
// Queries: the arc length of W1 within 1e-9; 10^4 parameters of W1 at equal
// arc length; curvature (Frenet frames) of W1 at 10^5 parameters; the
// principal curvatures of W3 on a 300 x 300 grid; tight bounding boxes of W1
// and W3 within 1e-9. Closest points and intersections are in query_bench.
//
// Checksums: counters, the sum of every output coordinate (or curvature,
// length, box side) so a change of result shows.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core_workloads.h"
#include "freeform/core/arc_length.h"
#include "freeform/core/bounding_box.h"
#include "freeform/core/curve.h"
#include "freeform/core/differential_geometry.h"
#include "freeform/core/mesh.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/surface.h"
#include "freeform/core/tensor_surface.h"
#include "workloads.h"

namespace {

using freeform::bench::UniformParameters;
using freeform::bench::W1Curve;
using freeform::bench::W3Surface;

// The curve and surface views `data`, which must outlive them.
freeform::Curve CurveOf(const freeform::BSplineCurveData& data) {
  return *freeform::BSplineCurve::Create(data.view());
}
freeform::Surface SurfaceOf(const freeform::SurfaceData& data) {
  return *freeform::BSplineSurface::Create(data.bspline_view());
}

double Sum(const std::vector<double>& values) {
  double sum = 0;
  for (const double value : values) sum += value;
  return sum;
}

// Counts `points` a run as the points/s counter.
void CountPoints(benchmark::State& state, size_t points) {
  state.counters["points/s"] = benchmark::Counter(
      static_cast<double>(points) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}

// The control nets of examples/teapot.json: the 48 numbers after each
// "control_points" (16 points of 3, row-major).
std::vector<std::vector<double>> TeapotNets() {
  std::ifstream file(FREEFORM_SOURCE_DIR "/examples/teapot.json");
  std::stringstream text;
  text << file.rdbuf();
  const std::string json = text.str();
  std::vector<std::vector<double>> nets;
  for (size_t at = json.find("\"control_points\""); at != std::string::npos;
       at = json.find("\"control_points\"", at)) {
    std::vector<double>& net = nets.emplace_back();
    at = json.find('[', at);
    while (net.size() < 48) {
      at = json.find_first_of("-0123456789", at);
      size_t used = 0;
      net.push_back(std::stod(json.substr(at, 32), &used));
      at += used;
    }
  }
  return nets;
}

// The argument is the tolerance's negative exponent (3: 1e-3).
void BM_TeapotTessellation(benchmark::State& state) {
  const std::vector<std::vector<double>> nets = TeapotNets();
  std::vector<freeform::Surface> patches;
  for (const std::vector<double>& net : nets) {
    patches.push_back(*freeform::BezierSurface::Create(
        {.control_net =
             {.dimension = 3, .count_u = 4, .count_v = 4, .coordinates = net},
         .weights = {}}));
  }
  double tolerance = 1;
  for (int64_t k = 0; k < state.range(0); ++k) tolerance /= 10;
  freeform::Mesh mesh;
  for (auto _ : state) {
    absl::StatusOr<freeform::Mesh> made = freeform::TessellateSurfaces(
        patches, {.tolerance = tolerance, .max_vertices = 1 << 24});
    if (!made.ok()) {
      state.SkipWithError(made.status().ToString().c_str());
      return;
    }
    mesh = *std::move(made);
  }
  state.counters["patches"] = static_cast<double>(patches.size());
  state.counters["vertices"] = static_cast<double>(mesh.vertices.size() / 3);
  state.counters["triangles"] = static_cast<double>(mesh.triangles.size() / 3);
  state.counters["checksum"] = Sum(mesh.vertices);
}
BENCHMARK(BM_TeapotTessellation)->Arg(3)->Arg(4)->Unit(benchmark::kMillisecond);

// Inserts `knots` into W1 and reports the result's size and checksum.
void InsertIntoW1(benchmark::State& state, const std::vector<double>& knots) {
  const freeform::BSplineCurveData w1 = W1Curve();
  freeform::BSplineCurveData refined;
  for (auto _ : state) {
    absl::StatusOr<freeform::BSplineCurveData> made =
        freeform::InsertKnots(w1.view(), knots);
    if (!made.ok()) {
      state.SkipWithError(made.status().ToString().c_str());
      return;
    }
    refined = *std::move(made);
  }
  state.counters["control_points"] =
      static_cast<double>(refined.coordinates.size() / 3);
  state.counters["checksum"] = Sum(refined.coordinates);
}

void BM_InsertOneKnotW1(benchmark::State& state) {
  InsertIntoW1(state, {0.37});
}
BENCHMARK(BM_InsertOneKnotW1)->Unit(benchmark::kMicrosecond);

void BM_RefineW1With1000Knots(benchmark::State& state) {
  std::vector<double> knots(1000);
  for (size_t k = 0; k < knots.size(); ++k) {
    knots[k] = (static_cast<double>(k) + 0.5) / 1000;
  }
  InsertIntoW1(state, knots);
}
BENCHMARK(BM_RefineW1With1000Knots)->Unit(benchmark::kMicrosecond);

// Times `decompose`, which returns the pieces (Bezier segments or patches),
// and reports their number and the sum of their coordinates.
template <typename Decompose>
void RunDecompose(benchmark::State& state, Decompose&& decompose) {
  auto pieces = decompose();
  for (auto _ : state) pieces = decompose();
  double checksum = 0;
  for (const auto& piece : pieces) checksum += Sum(piece.coordinates);
  state.counters["pieces"] = static_cast<double>(pieces.size());
  state.counters["checksum"] = checksum;
}

void BM_DecomposeW1(benchmark::State& state) {
  const freeform::BSplineCurveData w1 = W1Curve();
  RunDecompose(state, [&] {
    return freeform::DecomposeBSplineCurve(w1.view())->segments;
  });
}
BENCHMARK(BM_DecomposeW1)->Unit(benchmark::kMicrosecond);

void BM_DecomposeW3(benchmark::State& state) {
  const freeform::SurfaceData w3 = W3Surface();
  RunDecompose(state, [&] {
    return freeform::DecomposeBSplineSurface(w3.bspline_view())->patches;
  });
}
BENCHMARK(BM_DecomposeW3)->Unit(benchmark::kMicrosecond);

void BM_ArcLengthW1(benchmark::State& state) {
  const freeform::BSplineCurveData w1 = W1Curve();
  const freeform::Curve curve = CurveOf(w1);
  absl::StatusOr<double> length;
  for (auto _ : state) {
    length = freeform::ArcLength(curve, 0, 1, 1e-9);
    if (!length.ok()) {
      state.SkipWithError(length.status().ToString().c_str());
      return;
    }
  }
  state.counters["length"] = *length;
}
BENCHMARK(BM_ArcLengthW1)->Unit(benchmark::kMicrosecond);

void BM_EqualArcLengthW1(benchmark::State& state) {
  const freeform::BSplineCurveData w1 = W1Curve();
  const freeform::Curve curve = CurveOf(w1);
  std::vector<double> parameters(10'000);
  for (auto _ : state) {
    const absl::Status status = freeform::EqualArcLengthParameters(
        curve, 0, 1, parameters.size(), 1e-9, absl::MakeSpan(parameters));
    if (!status.ok()) state.SkipWithError(status.ToString().c_str());
  }
  state.counters["checksum"] = Sum(parameters);
}
BENCHMARK(BM_EqualArcLengthW1)->Unit(benchmark::kMillisecond);

void BM_CurvatureW1(benchmark::State& state) {
  const freeform::BSplineCurveData w1 = W1Curve();
  const freeform::Curve curve = CurveOf(w1);
  const std::vector<double> t = UniformParameters(100'000);
  const freeform::FrenetFrameSizes sizes = freeform::FrenetSizes(3, t.size());
  std::vector<double> curvatures(sizes.curvatures);
  std::vector<freeform::CurvePointStatus> statuses(sizes.statuses);
  const freeform::FrenetFrameOutput output{
      .curvatures = absl::MakeSpan(curvatures),
      .statuses = absl::MakeSpan(statuses)};
  for (auto _ : state) {
    const absl::Status status =
        freeform::EvaluateFrenetFrames(curve, t, output);
    if (!status.ok()) state.SkipWithError(status.ToString().c_str());
  }
  state.counters["checksum"] = Sum(curvatures);
  CountPoints(state, t.size());
}
BENCHMARK(BM_CurvatureW1)->Unit(benchmark::kMillisecond);

void BM_PrincipalCurvaturesW3(benchmark::State& state) {
  const freeform::SurfaceData w3 = W3Surface();
  const freeform::Surface surface = SurfaceOf(w3);
  const std::vector<double> grid = UniformParameters(300);
  const auto samples = freeform::SurfaceSamples::Grid(grid, grid);
  const size_t count = grid.size() * grid.size();
  const freeform::SurfaceCurvatureSizes sizes = freeform::CurvatureSizes(count);
  std::vector<double> mean(sizes.mean);
  std::vector<freeform::SurfacePointStatus> statuses(sizes.statuses);
  const freeform::SurfaceCurvatureOutput output{
      .mean = absl::MakeSpan(mean), .statuses = absl::MakeSpan(statuses)};
  for (auto _ : state) {
    const absl::Status status =
        freeform::EvaluateSurfaceCurvatures(surface, samples, output);
    if (!status.ok()) state.SkipWithError(status.ToString().c_str());
  }
  state.counters["checksum"] = Sum(mean);
  CountPoints(state, count);
}
BENCHMARK(BM_PrincipalCurvaturesW3)->Unit(benchmark::kMillisecond);

// Times `box` (returning a BoundingBox) and reports its sides' sum.
template <typename Box>
void RunBox(benchmark::State& state, Box&& box) {
  freeform::BoundingBox result;
  for (auto _ : state) result = box();
  state.counters["checksum"] = Sum(result.lower) + Sum(result.upper);
}

void BM_BoundingBoxW1(benchmark::State& state) {
  const freeform::BSplineCurveData w1 = W1Curve();
  const freeform::Curve curve = CurveOf(w1);
  RunBox(state, [&] { return *freeform::CurveBoundingBox(curve, 1e-9); });
}
BENCHMARK(BM_BoundingBoxW1)->Unit(benchmark::kMicrosecond);

void BM_BoundingBoxW3(benchmark::State& state) {
  const freeform::SurfaceData w3 = W3Surface();
  const freeform::Surface surface = SurfaceOf(w3);
  RunBox(state, [&] { return *freeform::SurfaceBoundingBox(surface, 1e-9); });
}
BENCHMARK(BM_BoundingBoxW3)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
