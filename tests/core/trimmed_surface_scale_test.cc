// Trimmed faces at scale (trimmed_surface.h): ten thousand holes, a loop of
// a hundred thousand segments, validated and classified against the
// closed-form answer. The timing of the same faces is bench/face_bench.cc.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "freeform/core/cancellation.h"
#include "freeform/core/thread_pool.h"
#include "freeform/core/trimmed_surface.h"
#include "trim_shapes.h"

namespace freeform {
namespace {

using trim_testing::BilinearPlane;
using trim_testing::ClockwiseCircle;
using trim_testing::LoopOf;
using trim_testing::PolygonVertex;

constexpr double kPi = std::numbers::pi;

std::vector<double> RandomPoints(size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0);
  std::vector<double> uv(2 * count);
  for (double& x : uv) x = coordinate(rng);
  return uv;
}

TEST(TrimmedSurfaceAtScale, TenThousandTinyHoles) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  constexpr int kSide = 100;
  const double r = 0.003;
  const std::vector<BSplineCurveData> circles =
      trim_testing::GridOfHoles(kSide, r);
  absl::StatusOr<TrimmedSurface> face =
      TrimmedSurface::Create({.surface = surface,
                              .outer = std::nullopt,
                              .holes = trim_testing::LoopsOf(circles)},
                             1e-9);
  ASSERT_TRUE(face.ok()) << face.status();
  const std::vector<double> uv = RandomPoints(10000, 3);
  absl::StatusOr<std::vector<PointLocation>> at =
      ClassifyPoints(*face, uv, 1e-9);
  ASSERT_TRUE(at.ok()) << at.status();
  int in_holes = 0;
  for (size_t k = 0; k < at->size(); ++k) {
    const double u = uv[2 * k], v = uv[2 * k + 1];
    const double du = u * kSide - std::floor(u * kSide) - 0.5;
    const double dv = v * kSide - std::floor(v * kSide) - 0.5;
    const double distance = std::hypot(du, dv) / kSide - r;
    if (std::abs(distance) < 1e-8) continue;
    in_holes += distance < 0;
    EXPECT_EQ((*at)[k],
              distance < 0 ? PointLocation::kOutside : PointLocation::kInside)
        << u << ", " << v;
  }
  // About pi r^2 kSide^2 (28%) of the points fall in holes.
  EXPECT_GT(in_holes, 2000);
  // On a pool, in chunks, the same answers; a cancelled token stops it.
  ThreadPool pool(2);
  absl::StatusOr<std::vector<PointLocation>> pooled =
      ClassifyPoints(*face, uv, 1e-9, {.pool = &pool, .grain = 256});
  ASSERT_TRUE(pooled.ok()) << pooled.status();
  EXPECT_EQ(*pooled, *at);
  CancellationToken cancel;
  cancel.Cancel();
  EXPECT_EQ(ClassifyPoints(*face, uv, 1e-9, {.cancellation = &cancel})
                .status()
                .code(),
            absl::StatusCode::kCancelled);
}

// ExpectPolygonClassification checks every point against the n-gon of
// radius 0.4 about (0.5, 0.5) less the disk of radius 0.1 there, skipping
// points within 1e-9 of either.
void ExpectPolygonClassification(int n, const std::vector<double>& uv,
                                 const std::vector<PointLocation>& at) {
  for (size_t k = 0; k < at.size(); ++k) {
    const std::array<double, 2> p = {uv[2 * k], uv[2 * k + 1]};
    double theta = std::atan2(p[1] - 0.5, p[0] - 0.5);
    if (theta < 0) theta += 2 * kPi;
    const int sector = static_cast<int>(theta / (2 * kPi) * n);
    const std::array<double, 2> a = PolygonVertex(n, 0.4, 0.5, 0.5, sector);
    const std::array<double, 2> b = PolygonVertex(n, 0.4, 0.5, 0.5, sector + 1);
    const double side =
        ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) /
        std::hypot(b[0] - a[0], b[1] - a[1]);
    const double to_hole = std::hypot(p[0] - 0.5, p[1] - 0.5) - 0.1;
    if (std::abs(side) < 1e-9 || std::abs(to_hole) < 1e-9) continue;
    const bool inside = side > 0 && to_hole > 0;
    EXPECT_EQ(at[k], inside ? PointLocation::kInside : PointLocation::kOutside)
        << p[0] << ", " << p[1];
  }
}

// The unit plane inside the regular n-gon of radius 0.4 about (0.5, 0.5),
// less the disk of radius 0.1 there; the data outlives the face.
struct PolygonWithHole {
  explicit PolygonWithHole(int n)
      : plane(BilinearPlane()),
        surface(*BezierSurface::Create(plane.bezier_view())),
        polygon(trim_testing::RegularPolygon(n, 0.4, 0.5, 0.5)),
        hole(ClockwiseCircle(0.1, 0.5, 0.5)),
        face(TrimmedSurface::Create({.surface = surface,
                                     .outer = LoopOf(polygon),
                                     .holes = {LoopOf(hole)}},
                                    1e-9)) {}

  SurfaceData plane;
  Surface surface;
  BSplineCurveData polygon;
  BSplineCurveData hole;
  absl::StatusOr<TrimmedSurface> face;
};

TEST(TrimmedSurfaceAtScale, ALoopOfAHundredThousandSegments) {
  constexpr int kSegments = 100000;
  const PolygonWithHole shape(kSegments);
  ASSERT_TRUE(shape.face.ok()) << shape.face.status();
  const std::vector<double> uv = RandomPoints(10000, 5);
  absl::StatusOr<std::vector<PointLocation>> at =
      ClassifyPoints(*shape.face, uv, 1e-12);
  ASSERT_TRUE(at.ok()) << at.status();
  ExpectPolygonClassification(kSegments, uv, *at);
}

TEST(TrimmedSurfaceAtScale, AreaOfAPolygonOfTenThousandSegments) {
  constexpr int kSegments = 10000;
  const PolygonWithHole shape(kSegments);
  ASSERT_TRUE(shape.face.ok()) << shape.face.status();
  absl::StatusOr<FaceAreaResult> area = FaceArea(*shape.face, 1e-11);
  ASSERT_TRUE(area.ok()) << area.status();
  const double polygon_area =
      0.5 * kSegments * 0.16 * std::sin(2 * kPi / kSegments);
  EXPECT_NEAR(area->area, polygon_area - kPi * 0.01, 1e-11);
}

}  // namespace
}  // namespace freeform
