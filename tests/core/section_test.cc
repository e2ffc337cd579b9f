#include "freeform/core/section.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "freeform/core/status.h"
#include "shapes.h"
#include "test_util.h"

namespace freeform {
namespace {

// CheckOnSurface checks that every vertex is the surface's point at its
// parameters.
void CheckOnSurface(const Surface& surface, const Sections& sections) {
  for (size_t r = 0; r < sections.parameters.size() / 2; ++r) {
    const std::vector<double> point = testing_util::SurfacePoints(
        surface, SurfaceSamples::Pairs(absl::MakeConstSpan(
                     sections.parameters.data() + 2 * r, 2)));
    for (int x = 0; x < 3; ++x) {
      ASSERT_NEAR(point[x], sections.points[3 * r + x], 1e-13);
    }
  }
}

TEST(SectionTest, PlaneSectionsOfASpherePatchAreCircles) {
  const double radius = 2.0;
  const SurfaceData data = testing_util::SpherePatch(radius);
  const absl::StatusOr<Surface> sphere =
      BezierSurface::Create(data.bezier_view());
  ASSERT_TRUE(sphere.ok());
  for (double h : {0.3, 1.0, 1.9}) {
    // z = h: the circle of radius sqrt(r^2 - h^2) about the z axis.
    const std::vector<double> point = {0, 0, h};
    const std::vector<double> normal = {0, 0, 1};
    const absl::StatusOr<Sections> sections =
        IntersectSurfacePlane(*sphere, point, normal, {.tolerance = 1e-6});
    ASSERT_TRUE(sections.ok()) << sections.status();
    ASSERT_EQ(sections->offsets.size(), 2u) << h;
    EXPECT_FALSE(sections->closed[0]);
    CheckOnSurface(*sphere, *sections);
    const double circle = std::sqrt(radius * radius - h * h);
    const size_t count = sections->offsets[1];
    EXPECT_GE(count, 3u);
    for (size_t r = 0; r < count; ++r) {
      const double* p = sections->points.data() + 3 * r;
      EXPECT_NEAR(p[2], h, 1e-12);
      EXPECT_NEAR(std::hypot(p[0], p[1]), circle, 1e-12);
    }
    // From one meridian of the patch to the other.
    const double* first = sections->points.data();
    const double* last = sections->points.data() + 3 * (count - 1);
    EXPECT_NEAR(std::min(std::abs(first[0]), std::abs(first[1])), 0.0, 1e-12);
    EXPECT_NEAR(std::min(std::abs(last[0]), std::abs(last[1])), 0.0, 1e-12);
    // Chords within the tolerance of the arc: sagitta of each segment.
    for (size_t r = 0; r + 1 < count; ++r) {
      const double* a = sections->points.data() + 3 * r;
      const double chord = std::hypot(a[3] - a[0], a[4] - a[1]);
      const double sagitta =
          circle - std::sqrt(circle * circle - chord * chord / 4);
      EXPECT_LE(sagitta, 1.01e-6);
    }
  }
  // x = c: the circle of radius sqrt(r^2 - c^2) about (c, 0, 0) in x = c.
  const double c = 0.8;
  const std::vector<double> point = {c, 5, -3};
  const std::vector<double> normal = {-3, 0, 0};
  const absl::StatusOr<Sections> sections =
      IntersectSurfacePlane(*sphere, point, normal);
  ASSERT_TRUE(sections.ok());
  ASSERT_EQ(sections->offsets.size(), 2u);
  for (size_t r = 0; r < sections->offsets[1]; ++r) {
    const double* p = sections->points.data() + 3 * r;
    EXPECT_NEAR(p[0], c, 1e-12);
    EXPECT_NEAR(std::hypot(p[1], p[2]), std::sqrt(radius * radius - c * c),
                1e-12);
  }
}

TEST(SectionTest, ClosedContourOfABump) {
  // A bicubic B-spline bump: 7 x 7 points on [0, 1]^2, the middle 3 x 3
  // raised to 1. Cut at z = 0.5 it gives one closed loop.
  std::vector<double> net;
  for (int i = 0; i < 7; ++i) {
    for (int j = 0; j < 7; ++j) {
      const bool middle = i >= 2 && i <= 4 && j >= 2 && j <= 4;
      net.insert(net.end(), {i / 6.0, j / 6.0, middle ? 1.0 : 0.0});
    }
  }
  const std::vector<double> knots = {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1};
  const absl::StatusOr<Surface> bump =
      BSplineSurface::Create({3, 3, {3, 7, 7, net}, knots, knots, {}});
  ASSERT_TRUE(bump.ok()) << bump.status();
  const std::vector<double> point = {0, 0, 0.5};
  const std::vector<double> normal = {0, 0, 2};
  const absl::StatusOr<Sections> sections =
      IntersectSurfacePlane(*bump, point, normal, {.tolerance = 1e-4});
  ASSERT_TRUE(sections.ok()) << sections.status();
  ASSERT_EQ(sections->offsets.size(), 2u);
  EXPECT_TRUE(sections->closed[0]);
  CheckOnSurface(*bump, *sections);
  const size_t count = sections->offsets[1];
  for (size_t r = 0; r < count; ++r) {
    EXPECT_NEAR(sections->points[3 * r + 2], 0.5, 1e-12);
  }
  for (int x = 0; x < 3; ++x) {
    EXPECT_NEAR(sections->points[x], sections->points[3 * (count - 1) + x],
                1e-9);
  }
}

// The section z = h of the sphere patch fitted as a B-spline: the curve,
// sampled densely (between the vertices too), stays on the circle of radius
// sqrt(r^2 - h^2) in z = h, from one meridian to the other.
TEST(SectionTest, FittedSectionOfTheSphereIsOnItsCircle) {
  const double radius = 2.0;
  const SurfaceData data = testing_util::SpherePatch(radius);
  const absl::StatusOr<Surface> sphere =
      BezierSurface::Create(data.bezier_view());
  ASSERT_TRUE(sphere.ok());
  for (const double fit : {1e-3, 1e-6}) {
    const double h = 1.2;
    const std::vector<double> point = {0, 0, h};
    const std::vector<double> normal = {0, 0, 1};
    const absl::StatusOr<Sections> sections = IntersectSurfacePlane(
        *sphere, point, normal, {.tolerance = 1e-5, .fit_tolerance = fit});
    ASSERT_TRUE(sections.ok()) << sections.status();
    ASSERT_EQ(sections->curves.size(), 1u);
    const absl::StatusOr<Curve> curve =
        BSplineCurve::Create(sections->curves[0].view());
    ASSERT_TRUE(curve.ok()) << curve.status();
    const ParameterDomain domain = DomainOf(*curve);
    const std::vector<double> t =
        testing_util::EvenlySpaced(domain.start, domain.end, 2001);
    const std::vector<double> samples = testing_util::CurvePoints(*curve, t);
    const double circle = std::sqrt(radius * radius - h * h);
    double worst = 0.0;
    for (size_t r = 0; r < t.size(); ++r) {
      const double* p = samples.data() + 3 * r;
      worst = std::max({worst, std::abs(p[2] - h),
                        std::abs(std::hypot(p[0], p[1]) - circle)});
    }
    // Within the fit tolerance at the vertices; between them a smooth fit
    // of a smooth curve stays as close (the polyline's own chords are 1e-5
    // from the arc, the fit is not bound to them).
    EXPECT_LE(worst, fit) << fit;
    const double* first = samples.data();
    const double* last = samples.data() + 3 * (t.size() - 1);
    EXPECT_NEAR(std::min(std::abs(first[0]), std::abs(first[1])), 0.0, 1e-12);
    EXPECT_NEAR(std::min(std::abs(last[0]), std::abs(last[1])), 0.0, 1e-12);
  }
  const std::vector<double> point = {0, 0, 1};
  const std::vector<double> up = {0, 0, 1};
  EXPECT_EQ(FieldPathOf(
                IntersectSurfacePlane(*sphere, point, up, {.fit_tolerance = -1})
                    .status()),
            "fit_tolerance");
  const absl::StatusOr<Sections> plain =
      IntersectSurfacePlane(*sphere, point, up);
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(plain->curves.empty());
}

TEST(SectionTest, ErrorsNameTheirField) {
  const SurfaceData data = testing_util::SpherePatch(1.0);
  const absl::StatusOr<Surface> sphere =
      BezierSurface::Create(data.bezier_view());
  const std::vector<double> point = {0, 0, 0};
  const std::vector<double> zero = {0, 0, 0};
  const std::vector<double> two = {0, 1};
  EXPECT_EQ(FieldPathOf(IntersectSurfacePlane(*sphere, point, zero).status()),
            "plane_normal");
  EXPECT_EQ(FieldPathOf(IntersectSurfacePlane(*sphere, two, point).status()),
            "plane_point");
  const std::vector<double> up = {0, 0, 1};
  const std::vector<double> half = {0, 0, 0.5};
  EXPECT_EQ(
      FieldPathOf(
          IntersectSurfacePlane(*sphere, half, up, {.tolerance = 0}).status()),
      "tolerance");
  const absl::Status over =
      IntersectSurfacePlane(*sphere, half, up,
                            {.tolerance = 1e-9, .max_points = 10})
          .status();
  EXPECT_EQ(over.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(FieldPathOf(over), "max_points");
}

}  // namespace
}  // namespace freeform
