#include "freeform/core/section.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
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
  // A closed polyline repeats its first vertex exactly (its last arc's end
  // was only within the chain's slack of it).
  for (int x = 0; x < 3; ++x) {
    EXPECT_EQ(sections->points[x], sections->points[3 * (count - 1) + x]);
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
  // Below what double precision resolves on the sphere (2^-48 of its
  // radius 2) no fit can pass within it: refused at once, naming it (it
  // was blamed on "parameters", an input of the fit that is not an option
  // of the section). Just above, the fit interpolates every vertex (least
  // squares with 512 control points for the 513 vertices was singular).
  for (const double tiny : {1e-300, 1e-16}) {
    EXPECT_EQ(FieldPathOf(IntersectSurfacePlane(
                              *sphere, point, up,
                              {.tolerance = 1e-5, .fit_tolerance = tiny})
                              .status()),
              "fit_tolerance")
        << tiny;
  }
  const absl::StatusOr<Sections> exact = IntersectSurfacePlane(
      *sphere, point, up, {.tolerance = 1e-5, .fit_tolerance = 1e-14});
  ASSERT_TRUE(exact.ok()) << exact.status();
  ASSERT_EQ(exact->curves.size(), 1u);
  const absl::StatusOr<Sections> plain =
      IntersectSurfacePlane(*sphere, point, up);
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(plain->curves.empty());
}

// The unit square of the plane z = 0 as a bilinear patch: S(u, v) =
// (u, v, 0).
absl::StatusOr<Surface> UnitSquare() {
  static const std::vector<double> net = {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0};
  return BezierSurface::Create({{3, 2, 2, net}, {}});
}

// ExpectRefused checks that `status` has `code` and names `field`.
void ExpectRefused(const absl::Status& status, absl::StatusCode code,
                   const std::string& field) {
  EXPECT_EQ(status.code(), code) << status;
  EXPECT_EQ(FieldPathOf(status), field) << status;
}

// VertexCount returns the polyline vertices and region corners of an
// answer, what max_points caps.
size_t VertexCount(const Sections& sections) {
  return sections.points.size() / 3 + sections.region_corners.size() / 2;
}

// CheckOnPlane checks that every vertex, evaluated at its parameters, lies
// within `tolerance` of the plane n . x = n . p (n of length 1).
void CheckOnPlane(const Surface& surface, const Sections& sections,
                  const std::vector<double>& p, const std::vector<double>& n,
                  double tolerance) {
  for (size_t r = 0; r < sections.parameters.size() / 2; ++r) {
    const std::vector<double> point = testing_util::SurfacePoints(
        surface, SurfaceSamples::Pairs(absl::MakeConstSpan(
                     sections.parameters.data() + 2 * r, 2)));
    double distance = 0.0;
    for (int x = 0; x < 3; ++x) distance += n[x] * (point[x] - p[x]);
    ASSERT_LE(std::abs(distance), tolerance) << "vertex " << r;
  }
}

// A plane holding the whole square is one region, its parameter square; a
// bicubic B-spline on knots 0^4, 1/7, ..., 6/7, 1^4 of 10 x 10 points on
// z = 0 but the middle 2 x 2 raised is z = 0 exactly where a raised
// point's basis function vanishes: u or v outside (1/7, 6/7), the 24 span
// rectangles around the border.
TEST(SectionTest, PartsInThePlaneAreRegions) {
  const absl::StatusOr<Surface> square = UnitSquare();
  const std::vector<double> origin = {0, 0, 0};
  const std::vector<double> up = {0, 0, 1};
  const absl::StatusOr<Sections> whole =
      IntersectSurfacePlane(*square, origin, up);
  ASSERT_TRUE(whole.ok()) << whole.status();
  EXPECT_EQ(whole->offsets.size(), 1u);  // no polyline
  ASSERT_EQ(whole->region_offsets.size(), 2u);
  EXPECT_EQ(whole->region_corners,
            (std::vector<double>{0, 0, 1, 0, 1, 1, 0, 1}));

  std::vector<double> net;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const bool raised = (i == 4 || i == 5) && (j == 4 || j == 5);
      net.insert(net.end(), {i / 9.0, j / 9.0, raised ? 1.0 : 0.0});
    }
  }
  std::vector<double> knots = {0, 0, 0, 0};
  for (int k = 1; k <= 6; ++k) knots.push_back(k / 7.0);
  knots.insert(knots.end(), {1, 1, 1, 1});
  const absl::StatusOr<Surface> bump =
      BSplineSurface::Create({3, 3, {3, 10, 10, net}, knots, knots, {}});
  ASSERT_TRUE(bump.ok()) << bump.status();
  const absl::StatusOr<Sections> border =
      IntersectSurfacePlane(*bump, origin, up);
  ASSERT_TRUE(border.ok()) << border.status();
  EXPECT_EQ(border->offsets.size(), 1u);
  ASSERT_EQ(border->region_offsets.size(), 25u);
  for (size_t k = 0; k + 1 < border->region_offsets.size(); ++k) {
    ASSERT_EQ(border->region_offsets[k + 1] - border->region_offsets[k], 4u);
    const double* corners =
        border->region_corners.data() + 2 * border->region_offsets[k];
    const double u0 = corners[0], v0 = corners[1], u1 = corners[4],
                 v1 = corners[5];
    EXPECT_NEAR((u1 - u0) * 7, 1.0, 1e-12);
    EXPECT_NEAR((v1 - v0) * 7, 1.0, 1e-12);
    const bool outside = u1 <= 1 / 7.0 + 1e-12 || u0 >= 6 / 7.0 - 1e-12 ||
                         v1 <= 1 / 7.0 + 1e-12 || v0 >= 6 / 7.0 - 1e-12;
    EXPECT_TRUE(outside) << "region at (" << u0 << ", " << v0 << ")";
  }
}

// A plane holding a boundary edge gives that edge as one polyline, on every
// side, with the patch on either side of the plane; a knot line the
// surface crosses the plane along is traced once (not once per piece).
TEST(SectionTest, EdgesInThePlaneAreFoundOnEverySide) {
  const absl::StatusOr<Surface> square = UnitSquare();
  struct Side {
    std::vector<double> point, normal;
  };
  const Side sides[] = {{{0, 0, 0}, {1, 0, 0}}, {{0, 5, 3}, {-2, 0, 0}},
                        {{1, 0, 0}, {1, 0, 0}}, {{1, 0, 0}, {-1, 0, 0}},
                        {{0, 0, 0}, {0, 1, 0}}, {{0, 0, 0}, {0, -3, 0}},
                        {{0, 1, 0}, {0, 1, 0}}, {{7, 1, 0}, {0, -1, 0}}};
  for (const Side& side : sides) {
    const absl::StatusOr<Sections> edge =
        IntersectSurfacePlane(*square, side.point, side.normal);
    ASSERT_TRUE(edge.ok()) << edge.status();
    ASSERT_EQ(edge->offsets.size(), 2u)
        << "plane through (" << side.point[0] << ", " << side.point[1]
        << ") normal (" << side.normal[0] << ", " << side.normal[1] << ")";
    EXPECT_FALSE(edge->closed[0]);
    const int axis = side.normal[0] != 0 ? 0 : 1;
    const size_t count = edge->offsets[1];
    for (size_t r = 0; r < count; ++r) {
      EXPECT_EQ(edge->points[3 * r + axis], side.point[axis]);
    }
    // From one corner to the other.
    EXPECT_EQ(std::abs(edge->points[1 - axis] -
                       edge->points[3 * (count - 1) + 1 - axis]),
              1.0);
  }
  // z = u - 1/2 as a bilinear B-spline with a knot at u = 1/2: z = 0 on the
  // knot line, the edge of both pieces.
  const std::vector<double> net = {0,   0, -0.5, 0, 1, -0.5, 0.5, 0, 0,
                                   0.5, 1, 0,    1, 0, 0.5,  1,   1, 0.5};
  const std::vector<double> knots_u = {0, 0, 0.5, 1, 1};
  const std::vector<double> knots_v = {0, 0, 1, 1};
  const absl::StatusOr<Surface> ramp =
      BSplineSurface::Create({1, 1, {3, 3, 2, net}, knots_u, knots_v, {}});
  ASSERT_TRUE(ramp.ok()) << ramp.status();
  // Seen from below, as the normal's sign does not matter.
  const absl::StatusOr<Sections> knot = IntersectSurfacePlane(
      *ramp, std::vector<double>(3, 0.0), std::vector<double>{0, 0, -1});
  ASSERT_TRUE(knot.ok()) << knot.status();
  ASSERT_EQ(knot->offsets.size(), 2u);
  EXPECT_FALSE(knot->closed[0]);
  for (size_t r = 0; r < knot->offsets[1]; ++r) {
    EXPECT_EQ(knot->points[3 * r], 0.5);
    EXPECT_EQ(knot->parameters[2 * r], 0.5);
  }
}

// The plane through (1/2, 0, 0) with normal (1, 1, 0) times any scale cuts
// the square along x + y = 1/2, from (1/2, 0) to (0, 1/2).
TEST(SectionTest, NormalsOfAnyScaleCutTheSame) {
  const absl::StatusOr<Surface> square = UnitSquare();
  const std::vector<double> point = {0.5, 0, 0};
  for (const double scale : {1.0, 1e155, 1e300, 1e-160, 1e-310}) {
    const std::vector<double> normal = {scale, scale, 0};
    const absl::StatusOr<Sections> cut =
        IntersectSurfacePlane(*square, point, normal);
    ASSERT_TRUE(cut.ok()) << scale << ": " << cut.status();
    ASSERT_EQ(cut->offsets.size(), 2u) << scale;
    const double unit = std::sqrt(0.5);
    CheckOnPlane(*square, *cut, point, {unit, unit, 0}, 1e-15);
    const size_t last = cut->offsets[1] - 1;
    const double ends[2] = {cut->points[0], cut->points[3 * last]};
    EXPECT_EQ(std::min(ends[0], ends[1]), 0.0);
    EXPECT_EQ(std::max(ends[0], ends[1]), 0.5);
  }
}

// A geometry scaled by 2^k is cut where the unscaled one is, scaled: the
// sphere patch of radius 2^k by z = 2^k / 2, far past where squared
// lengths overflow or underflow.
TEST(SectionTest, SectionsDoNotDependOnTheScale) {
  for (const int k : {0, 600, -600, 1000, -1000}) {
    const double radius = std::ldexp(1.0, k);
    const SurfaceData data = testing_util::SpherePatch(radius);
    const absl::StatusOr<Surface> sphere =
        BezierSurface::Create(data.bezier_view());
    const std::vector<double> point = {0, 0, radius / 2};
    const std::vector<double> up = {0, 0, 1};
    const absl::StatusOr<Sections> cut =
        IntersectSurfacePlane(*sphere, point, up, {.tolerance = 1e-6 * radius});
    ASSERT_TRUE(cut.ok()) << "2^" << k << ": " << cut.status();
    ASSERT_EQ(cut->offsets.size(), 2u) << "2^" << k;
    for (size_t r = 0; r < cut->offsets[1]; ++r) {
      const double* p = cut->points.data() + 3 * r;
      EXPECT_NEAR(p[2] / radius, 0.5, 1e-12);
      EXPECT_NEAR(std::hypot(p[0] / radius, p[1] / radius), std::sqrt(0.75),
                  1e-12);
    }
  }
}

// A rational patch of 3 x 3 points on z = 0 but the middle one at z = 1,
// of weight w: cut by z = 1/2, every vertex lies within the tolerance of
// the plane (evaluated at its parameters), or the call is refused naming
// the surface where double precision cannot place one so (near the edges
// the surface climbs from 0 to 1 over about 1/w of the parameters).
TEST(SectionTest, ExtremeWeightsAreCutCorrectlyOrRefused) {
  const std::vector<double> net = {0,   0, 0, 0,   0.5, 0, 0,   1, 0,
                                   0.5, 0, 0, 0.5, 0.5, 1, 0.5, 1, 0,
                                   1,   0, 0, 1,   0.5, 0, 1,   1, 0};
  const std::vector<double> point = {0, 0, 0.5};
  const std::vector<double> up = {0, 0, 1};
  int refused = 0;
  for (const double w : {1e5, 1e10, 1e15, 1e20, 1e50, 1e100}) {
    const std::vector<double> weights = {1, 1, 1, 1, w, 1, 1, 1, 1};
    const absl::StatusOr<Surface> patch =
        BezierSurface::Create({{3, 3, 3, net}, weights});
    ASSERT_TRUE(patch.ok()) << patch.status();
    const double tolerance = 1e-6;
    const absl::StatusOr<Sections> cut =
        IntersectSurfacePlane(*patch, point, up, {.tolerance = tolerance});
    if (!cut.ok()) {
      ExpectRefused(cut.status(), absl::StatusCode::kInvalidArgument,
                    "surface");
      ++refused;
      continue;
    }
    EXPECT_EQ(cut->offsets.size(), 2u) << "weight " << w;
    CheckOnPlane(*patch, *cut, point, up, tolerance);
  }
  // 1e20 and beyond cannot be resolved near u = 1 (1 - 1e-20 is 1).
  EXPECT_GE(refused, 3);
}

// The plane x = 0 cuts ShortSpanWall(origin) along v = origin + 0.3125:
// at origin 0 a segment from z = -1 to 1 on the surface at its parameters;
// at 1e15, where no double is that v and the surface at the nearest ones is
// 2 from the plane, the call is refused naming the surface rather than
// give vertices whose parameters are not theirs (a fuzz finding: a vertex
// at v = 2e15 where the surface was 1.0 away).
TEST(SectionTest, AParameterNoDoubleResolvesIsRefused) {
  const std::vector<double> point = {0, 0, 0};
  const std::vector<double> normal = {1, 0, 0};
  for (const double origin : {1e15, 0.0}) {
    const SurfaceData data = testing_util::ShortSpanWall(origin);
    const absl::StatusOr<Surface> wall =
        BSplineSurface::Create(data.bspline_view());
    ASSERT_TRUE(wall.ok()) << wall.status();
    const absl::StatusOr<Sections> cut =
        IntersectSurfacePlane(*wall, point, normal, {.tolerance = 1e-6});
    if (origin != 0.0) {
      ExpectRefused(cut.status(), absl::StatusCode::kInvalidArgument,
                    "surface");
      continue;
    }
    ASSERT_TRUE(cut.ok()) << cut.status();
    ASSERT_EQ(cut->offsets.size(), 2u);
    CheckOnSurface(*wall, *cut);
    for (size_t r = 0; r < cut->parameters.size() / 2; ++r) {
      EXPECT_NEAR(cut->parameters[2 * r + 1], 0.3125, 1e-12);
      EXPECT_NEAR(cut->points[3 * r], 0.0, 1e-12);
    }
  }
}

// max_points caps the vertices returned exactly: the cut x = 1/2 of the
// square is a segment of 3 vertices, the section z = 1 of the sphere patch
// N of them, the square in z = 0 a region of 4 corners.
// Arc ends are joined only within the tolerance: on a surface about 1e10
// from the origin (a space curve of degree 3 swept by degree 0 in u, a
// campaign finding), 1e-9 of the largest coordinate is 10, far above the
// tolerance 0.5, and a closed polyline's last vertex took the first one's
// point 1.5 from the surface at its own parameters. Every vertex is on the
// surface at its parameters and in the plane, within the tolerance, and a
// closed polyline ends at its first vertex, point and parameters.
TEST(SectionTest, ArcEndsJoinOnlyWithinTheTolerance) {
  const std::vector<double> net = {
      10000000000,        10000000000,        10000000000,
      10000000000,        10000000000,        10000000000,
      10000000000,        10000000001.113636, 10000000001.386364,
      10000000000,        10000000003,        10000000002,
      10000000001,        10000000002.795454, 10000000000.704546,
      10000000001.789135, 10000000000.022728, 10000000001.977272,
      10000000003,        10000000000.59091,  10000000001.385876,
      10000000003,        10000000002.818182, 10000000000.181818,
      10000000004,        10000000001.15909,  10000000000.738636,
      10000000004,        10000000001.15909,  10000000000.738636,
      10000000004,        10000000001.15909,  10000000000.738636,
      10000000004,        10000000003,        10000000001,
      10000000004,        10000000001.181818, 10000000000.772728,
      10000000004,        10000000001.181818, 10000000000.772728,
      10000000004,        10000000001.181818, 10000000000.772728,
      10000000004,        10000000002.295454, 10000000001.704546,
      10000000004,        10000000001.75,     10000000001.625,
      10000000004,        10000000001.204546, 10000000000.806818,
      10000000004,        10000000000.65909,  10000000000.84091};
  const std::vector<double> knots_u = {0, 1};
  const std::vector<double> knots_v = {
      0,      0,      0.03125, 0.0625, 0.09375, 0.125,  0.125, 0.15625,
      0.1875, 0.25,   0.25,    0.3125, 0.375,   0.4375, 0.5,   0.5625,
      0.625,  0.6875, 0.75,    0.8125, 0.875,   0.9375, 1};
  const absl::StatusOr<Surface> surface =
      BSplineSurface::Create({0, 3, {3, 1, 19, net}, knots_u, knots_v, {}});
  ASSERT_TRUE(surface.ok()) << surface.status();
  const std::vector<double> point = {0.5, 0.5, 0.5};
  const std::vector<double> normal = {0, -1, 1};
  const double tolerance = 0.5;
  const absl::StatusOr<Sections> sections =
      IntersectSurfacePlane(*surface, point, normal, {.tolerance = tolerance});
  ASSERT_TRUE(sections.ok()) << sections.status();
  ASSERT_GE(sections->offsets.size(), 2u);
  // Rounding of coordinates near 1e10 (ulp 2e-6) on top of the tolerance.
  const double allowed = tolerance + 1e-5;
  for (size_t r = 0; r < sections->parameters.size() / 2; ++r) {
    const std::vector<double> on_surface = testing_util::SurfacePoints(
        *surface, SurfaceSamples::Pairs(absl::MakeConstSpan(
                      sections->parameters.data() + 2 * r, 2)));
    double distance = 0.0;
    for (int x = 0; x < 3; ++x) {
      const double d = on_surface[x] - sections->points[3 * r + x];
      distance += d * d;
    }
    EXPECT_LE(std::sqrt(distance), allowed) << "vertex " << r;
    const double height =
        (sections->points[3 * r + 2] - sections->points[3 * r + 1]) /
        std::sqrt(2.0);
    EXPECT_LE(std::abs(height), allowed) << "vertex " << r;
  }
  for (size_t k = 0; k + 1 < sections->offsets.size(); ++k) {
    if (!sections->closed[k]) continue;
    const size_t first = sections->offsets[k];
    const size_t last = sections->offsets[k + 1] - 1;
    for (int x = 0; x < 3; ++x) {
      EXPECT_EQ(sections->points[3 * first + x],
                sections->points[3 * last + x]);
    }
    for (int x = 0; x < 2; ++x) {
      EXPECT_EQ(sections->parameters[2 * first + x],
                sections->parameters[2 * last + x]);
    }
  }
}

TEST(SectionTest, MaxPointsIsExact) {
  const absl::StatusOr<Surface> square = UnitSquare();
  const SurfaceData data = testing_util::SpherePatch(2.0);
  const absl::StatusOr<Surface> sphere =
      BezierSurface::Create(data.bezier_view());
  struct Case {
    const Surface* surface;
    std::vector<double> point, normal;
    double tolerance;
  };
  const Case cases[] = {{&*square, {0.5, 0, 0}, {1, 0, 0}, 1e-6},
                        {&*sphere, {0, 0, 1}, {0, 0, 1}, 1e-9},
                        {&*square, {0, 0, 0}, {0, 0, 1}, 1e-6}};
  const size_t expected[] = {3, 0, 4};
  for (size_t c = 0; c < 3; ++c) {
    const Case& each = cases[c];
    const absl::StatusOr<Sections> all = IntersectSurfacePlane(
        *each.surface, each.point, each.normal, {.tolerance = each.tolerance});
    ASSERT_TRUE(all.ok()) << all.status();
    const size_t n = VertexCount(*all);
    if (expected[c] > 0) {
      EXPECT_EQ(n, expected[c]);
    }
    const absl::StatusOr<Sections> exact =
        IntersectSurfacePlane(*each.surface, each.point, each.normal,
                              {.tolerance = each.tolerance, .max_points = n});
    ASSERT_TRUE(exact.ok()) << exact.status();
    EXPECT_EQ(VertexCount(*exact), n);
    for (const size_t cap : {n - 1, size_t{1}}) {
      SCOPED_TRACE(absl::StrCat("case ", c, " cap ", cap, " of ", n));
      ExpectRefused(IntersectSurfacePlane(
                        *each.surface, each.point, each.normal,
                        {.tolerance = each.tolerance, .max_points = cap})
                        .status(),
                    absl::StatusCode::kResourceExhausted, "max_points");
    }
  }
}

// Bad options are named; a tolerance below 2^-48 of the largest coordinate
// (1 for the sphere patch of radius 1) is refused at once, and the
// quadtree's work is bounded.
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
  for (const double tolerance : {5e-324, 1e-15, 3e-15}) {
    ExpectRefused(
        IntersectSurfacePlane(*sphere, half, up, {.tolerance = tolerance})
            .status(),
        absl::StatusCode::kInvalidArgument, "tolerance");
  }
  ExpectRefused(
      IntersectSurfacePlane(*sphere, half, up, {.max_work = 100}).status(),
      absl::StatusCode::kResourceExhausted, "max_work");
}

}  // namespace
}  // namespace freeform
