// Trimmed faces at scale (trimmed_surface.h): ten thousand holes, a loop of
// a hundred thousand segments, validated and classified against the
// closed-form answer. The timing of the same faces is bench/face_bench.cc.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "freeform/core/trimmed_surface.h"
#include "trim_shapes.h"

namespace freeform {
namespace {

using trim_testing::BilinearPlane;
using trim_testing::ClockwiseCircle;
using trim_testing::LoopOf;

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
  std::vector<BSplineCurveData> circles;
  std::vector<TrimLoop> holes;
  for (int i = 0; i < kSide; ++i) {
    for (int j = 0; j < kSide; ++j) {
      circles.push_back(
          ClockwiseCircle(r, (i + 0.5) / kSide, (j + 0.5) / kSide));
    }
  }
  for (const BSplineCurveData& circle : circles) {
    holes.push_back(LoopOf(circle));
  }
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(
      {.surface = surface, .outer = std::nullopt, .holes = std::move(holes)},
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
  // About pi r^2 kSide^2 of the points fall in holes.
  EXPECT_GT(in_holes, 150);
}

TEST(TrimmedSurfaceAtScale, ALoopOfAHundredThousandSegments) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  constexpr int kSegments = 100000;
  const double radius = 0.4;
  // The regular polygon as one degree-1 B-spline, counter-clockwise.
  BSplineCurveData polygon{.degree = 1, .dimension = 2};
  const auto vertex = [&](int k) {
    const double theta = 2 * kPi * (k % kSegments) / kSegments;
    return std::array<double, 2>{0.5 + radius * std::cos(theta),
                                 0.5 + radius * std::sin(theta)};
  };
  for (int k = 0; k <= kSegments; ++k) {
    polygon.coordinates.push_back(vertex(k)[0]);
    polygon.coordinates.push_back(vertex(k)[1]);
  }
  polygon.knots.push_back(0.0);
  for (int k = 0; k <= kSegments; ++k) {
    polygon.knots.push_back(static_cast<double>(k) / kSegments);
  }
  polygon.knots.push_back(1.0);
  const BSplineCurveData hole = ClockwiseCircle(0.1, 0.5, 0.5);
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(
      {.surface = surface, .outer = LoopOf(polygon), .holes = {LoopOf(hole)}},
      1e-9);
  ASSERT_TRUE(face.ok()) << face.status();
  const std::vector<double> uv = RandomPoints(10000, 5);
  absl::StatusOr<std::vector<PointLocation>> at =
      ClassifyPoints(*face, uv, 1e-12);
  ASSERT_TRUE(at.ok()) << at.status();
  for (size_t k = 0; k < at->size(); ++k) {
    const std::array<double, 2> p = {uv[2 * k], uv[2 * k + 1]};
    // The polygon's edge in the point's sector, and the hole's distance.
    double theta = std::atan2(p[1] - 0.5, p[0] - 0.5);
    if (theta < 0) theta += 2 * kPi;
    const int sector = static_cast<int>(theta / (2 * kPi) * kSegments);
    const std::array<double, 2> a = vertex(sector), b = vertex(sector + 1);
    const double edge = std::hypot(b[0] - a[0], b[1] - a[1]);
    const double side =
        ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) /
        edge;
    const double to_hole = std::hypot(p[0] - 0.5, p[1] - 0.5) - 0.1;
    if (std::abs(side) < 1e-9 || std::abs(to_hole) < 1e-9) continue;
    const bool inside = side > 0 && to_hole > 0;
    EXPECT_EQ((*at)[k], inside ? PointLocation::kInside : PointLocation::kOutside)
        << p[0] << ", " << p[1];
  }
  absl::StatusOr<FaceAreaResult> area = FaceArea(*face, 1e-10);
  ASSERT_TRUE(area.ok()) << area.status();
  const double polygon_area =
      0.5 * kSegments * radius * radius * std::sin(2 * kPi / kSegments);
  EXPECT_NEAR(area->area, polygon_area - kPi * 0.01, 1e-10);
}

}  // namespace
}  // namespace freeform
