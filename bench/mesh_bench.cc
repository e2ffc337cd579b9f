// Meshing and fitting benchmarks (issue #13):
//
//   build/release/bench/mesh_bench --benchmark_min_time=1
//
// M1: the NURBS torus of radii 3 and 1 (nine-point quadratic circles both
// ways) meshed within 1e-3, closed; also with a normal-angle limit of 50 or
// 20 milliradians (the mesh within 1e-3 holds 50 already, so that costs
// only the check). M2: the W3 surface (bicubic B-spline, 20 x 20 points
// from LCG seed 2, clamped uniform knots) meshed within 1e-3. F1: 10^5
// samples of the W1 curve (RandomSpline(1, 100, 3)) with noise of 1e-4,
// fitted to a tolerance of 5e-4. F2: 10^4 scattered samples of the W3
// surface at given (u, v), fitted by a bicubic 16 x 16 net.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "core_workloads.h"
#include "freeform/core/bspline.h"
#include "freeform/core/fitting.h"
#include "freeform/core/mesh.h"
#include "freeform/core/surface.h"
#include "freeform/core/tensor_surface.h"
#include "workloads.h"

namespace {

using freeform::bench::NurbsTorus;
using freeform::bench::RandomSpline;
using freeform::bench::W3Surface;

void MeshSurface(benchmark::State& state, const freeform::SurfaceData& data,
                 double tolerance, double max_normal_angle = 0) {
  const freeform::Surface surfaces[] = {
      *freeform::BSplineSurface::Create(data.bspline_view())};
  size_t vertices = 0;
  for (auto _ : state) {
    absl::StatusOr<freeform::Mesh> mesh = freeform::TessellateSurfaces(
        surfaces, {.tolerance = tolerance,
                   .max_normal_angle = max_normal_angle,
                   .max_vertices = 1 << 24});
    if (!mesh.ok()) {
      state.SkipWithError(mesh.status().ToString().c_str());
      return;
    }
    vertices = mesh->vertices.size() / 3;
    benchmark::DoNotOptimize(mesh->vertices.data());
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["vertices/s"] = benchmark::Counter(
      static_cast<double>(vertices) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}

void BM_M1_TorusMesh(benchmark::State& state) {
  MeshSurface(state, NurbsTorus(3.0, 1.0), 1e-3);
}
BENCHMARK(BM_M1_TorusMesh)->Unit(benchmark::kMillisecond);

// The argument is the limit in milliradians.
void BM_M1_TorusMeshNormalAngle(benchmark::State& state) {
  MeshSurface(state, NurbsTorus(3.0, 1.0), 1e-3,
              static_cast<double>(state.range(0)) / 1000);
}
BENCHMARK(BM_M1_TorusMeshNormalAngle)
    ->Arg(50)
    ->Arg(20)
    ->Unit(benchmark::kMillisecond);

void BM_M2_W3SurfaceMesh(benchmark::State& state) {
  MeshSurface(state, W3Surface(), 1e-3);
}
BENCHMARK(BM_M2_W3SurfaceMesh)->Unit(benchmark::kMillisecond);

void BM_F1_FitNoisyCurve(benchmark::State& state) {
  const freeform::bench::SplineData w1 = RandomSpline(1, 100, 3);
  const freeform::BSplineCurveView curve{
      .degree = 3,
      .control_points = {.dimension = 3, .coordinates = w1.points},
      .knots = w1.knots,
      .weights = {}};
  constexpr size_t kCount = 100000;
  std::vector<double> t(kCount);
  for (size_t k = 0; k < kCount; ++k) {
    t[k] = static_cast<double>(k) / (kCount - 1.0);
  }
  std::vector<double> points(3 * kCount);
  const absl::Span<double> output[] = {absl::MakeSpan(points)};
  if (!freeform::EvaluateBSplineCurve(curve, t, output).ok()) {
    state.SkipWithError("evaluation failed");
    return;
  }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> noise(-1e-4, 1e-4);
  for (double& x : points) x += noise(rng);
  int control_points = 0;
  for (auto _ : state) {
    absl::StatusOr<freeform::CurveFit> fit =
        freeform::FitCurve({.dimension = 3, .coordinates = points},
                           {.degree = 3, .tolerance = 5e-4, .parameters = t});
    if (!fit.ok()) {
      state.SkipWithError(fit.status().ToString().c_str());
      return;
    }
    control_points = static_cast<int>(fit->curve.coordinates.size() / 3);
    benchmark::DoNotOptimize(fit->max_residual);
  }
  state.counters["control_points"] = control_points;
}
BENCHMARK(BM_F1_FitNoisyCurve)->Unit(benchmark::kMillisecond);

void BM_F2_FitScatteredSurface(benchmark::State& state) {
  const freeform::SurfaceData w3 = W3Surface();
  constexpr size_t kCount = 10000;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> uv(2 * kCount);
  for (double& x : uv) x = unit(rng);
  std::vector<double> points(3 * kCount);
  const absl::Span<double> output[] = {absl::MakeSpan(points)};
  if (!freeform::EvaluateBSplineSurface(
           w3.bspline_view(), freeform::SurfaceSamples::Pairs(uv), output)
           .ok()) {
    state.SkipWithError("evaluation failed");
    return;
  }
  for (auto _ : state) {
    absl::StatusOr<freeform::ScatteredFit> fit = freeform::FitScatteredSurface(
        {.dimension = 3, .coordinates = points},
        {.control_count_u = 16, .control_count_v = 16, .parameters = uv});
    if (!fit.ok()) {
      state.SkipWithError(fit.status().ToString().c_str());
      return;
    }
    benchmark::DoNotOptimize(fit->max_residual);
  }
}
BENCHMARK(BM_F2_FitScatteredSurface)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
