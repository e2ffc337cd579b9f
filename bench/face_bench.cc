// Trimmed faces (issue #32): validation, classification and area at the
// scale of the unit tests' faces (tests/core/trimmed_surface_scale_test.cc):
//
//   build/release/bench/face_bench --benchmark_min_time=1
//
// Holes: the unit plane with 100 x 100 holes of radius 0.003 (NURBS
// circles), tolerance 1e-9. Polygon: the unit plane inside the regular
// 10^5-gon of radius 0.4 (one degree-1 B-spline) with a round hole of
// radius 0.1. Create validates and precomputes the face; Classify puts 10^4
// uniform random points (seed 3) in or out, classification tolerance 1e-9;
// Area is FaceArea to 1e-10 (of the 10^4-gon for the polygon). BoundingBox
// is FaceBoundingBox to 1e-6 of the plane inside a circle of radius 0.3,
// every side on the trim. FaceMesh is TessellateFace of the quarter
// cylinder of radius 1.5 and height 2 inside the window [0.1, 0.9] x
// [0.05, 0.95] with a round hole of radius 0.15 about (0.5, 0.5) in
// (u, v), at a 3D tolerance of 1e-3 and 1e-4 (vertices and triangles as
// counters); FullCylinder the full NURBS cylinder's window with a hole.
#include <benchmark/benchmark.h>

#include <optional>
#include <random>
#include <vector>

#include "freeform/core/face_mesh.h"
#include "freeform/core/surface.h"
#include "freeform/core/trimmed_surface.h"
#include "trim_shapes.h"

namespace {

using freeform::BSplineCurveData;
using freeform::TrimmedSurface;
using freeform::TrimmedSurfaceParts;

const freeform::SurfaceData& Plane() {
  static const freeform::SurfaceData plane =
      freeform::trim_testing::BilinearPlane();
  return plane;
}

freeform::Surface PlaneSurface() {
  return *freeform::BezierSurface::Create(Plane().bezier_view());
}

const std::vector<BSplineCurveData>& Holes() {
  static const std::vector<BSplineCurveData> holes =
      freeform::trim_testing::GridOfHoles(100, 0.003);
  return holes;
}

const BSplineCurveData& Polygon(int segments) {
  static const BSplineCurveData large =
      freeform::trim_testing::RegularPolygon(100000, 0.4, 0.5, 0.5);
  static const BSplineCurveData small =
      freeform::trim_testing::RegularPolygon(10000, 0.4, 0.5, 0.5);
  return segments == 100000 ? large : small;
}

const BSplineCurveData& RoundHole() {
  static const BSplineCurveData hole =
      freeform::trim_testing::ClockwiseCircle(0.1, 0.5, 0.5);
  return hole;
}

TrimmedSurfaceParts HolesParts() {
  return {.surface = PlaneSurface(),
          .outer = std::nullopt,
          .holes = freeform::trim_testing::LoopsOf(Holes())};
}

TrimmedSurfaceParts PolygonParts(int segments) {
  return {.surface = PlaneSurface(),
          .outer = freeform::trim_testing::LoopOf(Polygon(segments)),
          .holes = {freeform::trim_testing::LoopOf(RoundHole())}};
}

std::vector<double> RandomPoints() {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0);
  std::vector<double> uv(20000);
  for (double& x : uv) x = coordinate(rng);
  return uv;
}

void Create(benchmark::State& state, TrimmedSurfaceParts (*parts)()) {
  for (auto _ : state) {
    absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(parts(), 1e-9);
    if (!face.ok()) {
      state.SkipWithError(face.status().ToString().c_str());
      return;
    }
    benchmark::DoNotOptimize(&*face);
  }
}

void Classify(benchmark::State& state, TrimmedSurfaceParts (*parts)()) {
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(parts(), 1e-9);
  const std::vector<double> uv = RandomPoints();
  if (!face.ok()) {
    state.SkipWithError(face.status().ToString().c_str());
    return;
  }
  for (auto _ : state) {
    absl::StatusOr<std::vector<freeform::PointLocation>> at =
        freeform::ClassifyPoints(*face, uv, 1e-9);
    benchmark::DoNotOptimize(at->data());
  }
  state.counters["points/s"] =
      benchmark::Counter(1e4 * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
}

void Area(benchmark::State& state, TrimmedSurfaceParts (*parts)()) {
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(parts(), 1e-9);
  if (!face.ok()) {
    state.SkipWithError(face.status().ToString().c_str());
    return;
  }
  for (auto _ : state) {
    absl::StatusOr<freeform::FaceAreaResult> area =
        freeform::FaceArea(*face, 1e-10);
    benchmark::DoNotOptimize(area->area);
  }
}

// The plane inside the circle of radius 0.3 about (0.5, 0.45): every side
// of its box lies on the trim.
const BSplineCurveData& Disk() {
  static const BSplineCurveData disk =
      freeform::testing_util::NurbsCircle(0.3, 0.5, 0.45);
  return disk;
}

void BM_FaceBoundingBox_Disk(benchmark::State& state) {
  absl::StatusOr<TrimmedSurface> face =
      TrimmedSurface::Create({.surface = PlaneSurface(),
                              .outer = freeform::trim_testing::LoopOf(Disk()),
                              .holes = {}},
                             1e-9);
  if (!face.ok()) {
    state.SkipWithError(face.status().ToString().c_str());
    return;
  }
  for (auto _ : state) {
    absl::StatusOr<freeform::BoundingBox> box =
        freeform::FaceBoundingBox(*face, 1e-6);
    benchmark::DoNotOptimize(box->upper.data());
  }
}
BENCHMARK(BM_FaceBoundingBox_Disk)->Unit(benchmark::kMillisecond);

void BM_FaceMesh_Cylinder(benchmark::State& state) {
  const freeform::SurfaceData data =
      freeform::trim_testing::QuarterCylinder(1.5, 2.0);
  const std::vector<freeform::BezierCurveData> window =
      freeform::trim_testing::Square(0.1, 0.05, 0.9, 0.95);
  const BSplineCurveData hole =
      freeform::trim_testing::ClockwiseCircle(0.15, 0.5, 0.5);
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(
      {.surface = *freeform::BezierSurface::Create(data.bezier_view()),
       .outer = freeform::trim_testing::LoopOf(window),
       .holes = {freeform::trim_testing::LoopOf(hole)}},
      1e-9);
  if (!face.ok()) {
    state.SkipWithError(face.status().ToString().c_str());
    return;
  }
  const double tolerance = state.range(0) == 3 ? 1e-3 : 1e-4;
  size_t vertices = 0, triangles = 0;
  for (auto _ : state) {
    absl::StatusOr<freeform::FaceMesh> mesh =
        freeform::TessellateFace(*face, {.tolerance = tolerance});
    if (!mesh.ok()) {
      state.SkipWithError(mesh.status().ToString().c_str());
      return;
    }
    vertices = mesh->uv.size() / 2;
    triangles = mesh->triangles.size() / 3;
    benchmark::DoNotOptimize(mesh->vertices.data());
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_FaceMesh_Cylinder)->Arg(3)->Arg(4)->Unit(benchmark::kMillisecond);

// The full NURBS cylinder (9-point circle, C0 homogeneous lines at its
// double knots) inside trim_testing::WindowWithHole, at 1e-3.
void BM_FaceMesh_FullCylinder(benchmark::State& state) {
  const freeform::SurfaceData data = freeform::testing_util::Revolve(
      {{1.5, 0, 1}, {1.5, 1, 1}, {1.5, 2, 1}}, {0, 0, 0, 1, 1, 1});
  const freeform::Surface surface =
      *freeform::BSplineSurface::Create(data.bspline_view());
  const freeform::trim_testing::WindowWithHole shape(surface);
  if (!shape.face.ok()) {
    state.SkipWithError(shape.face.status().ToString().c_str());
    return;
  }
  size_t vertices = 0;
  for (auto _ : state) {
    absl::StatusOr<freeform::FaceMesh> mesh =
        freeform::TessellateFace(*shape.face, {.tolerance = 1e-3});
    if (!mesh.ok()) {
      state.SkipWithError(mesh.status().ToString().c_str());
      return;
    }
    vertices = mesh->uv.size() / 2;
    benchmark::DoNotOptimize(mesh->vertices.data());
  }
  state.counters["vertices"] = static_cast<double>(vertices);
}
BENCHMARK(BM_FaceMesh_FullCylinder)->Unit(benchmark::kMillisecond);

TrimmedSurfaceParts LargePolygon() { return PolygonParts(100000); }
TrimmedSurfaceParts SmallPolygon() { return PolygonParts(10000); }

void BM_FaceCreate_10kHoles(benchmark::State& s) { Create(s, HolesParts); }
void BM_FaceClassify_10kHoles(benchmark::State& s) { Classify(s, HolesParts); }
void BM_FaceArea_10kHoles(benchmark::State& s) { Area(s, HolesParts); }
void BM_FaceCreate_100kGon(benchmark::State& s) { Create(s, LargePolygon); }
void BM_FaceClassify_100kGon(benchmark::State& s) { Classify(s, LargePolygon); }
void BM_FaceArea_10kGon(benchmark::State& s) { Area(s, SmallPolygon); }

BENCHMARK(BM_FaceCreate_10kHoles)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FaceClassify_10kHoles)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FaceArea_10kHoles)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FaceCreate_100kGon)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FaceClassify_100kGon)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FaceArea_10kGon)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
