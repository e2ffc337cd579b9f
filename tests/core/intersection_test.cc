#include "freeform/core/intersection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "freeform/core/status.h"
#include "freeform/core/subdivision.h"
#include "shapes.h"
#include "test_util.h"

namespace freeform {
namespace {

std::vector<double> CurvePoint(const Curve& curve, double t) {
  return testing_util::CurvePoints(curve, {t});
}

std::vector<double> SurfacePoint(const Surface& surface, double u, double v) {
  const double uv[2] = {u, v};
  return testing_util::SurfacePoints(surface, SurfaceSamples::Pairs(uv));
}

double Distance(const std::vector<double>& a, const std::vector<double>& b) {
  return testing_util::PointDistance(a.data(), b.data(),
                                     static_cast<int>(a.size()));
}

// Graph returns the power-form curve (t, f(t)[, h(t)]) for the cubic f with
// coefficients f[0..3] (and h, when given).
absl::StatusOr<Curve> Graph(const std::vector<double>& f,
                            const std::vector<double>& h,
                            std::vector<double>& storage) {
  const int dim = h.empty() ? 2 : 3;
  storage.clear();
  for (int k = 0; k < 4; ++k) {
    storage.push_back(k == 1 ? 1.0 : 0.0);
    storage.push_back(f[k]);
    if (dim == 3) storage.push_back(h[k]);
  }
  return BezierCurve::FromPowerForm({dim, storage});
}

// Cubic returns the coefficients of c (t - r0)(t - r1)(t - r2).
std::vector<double> Cubic(double c, double r0, double r1, double r2) {
  return {-c * r0 * r1 * r2, c * (r0 * r1 + r0 * r2 + r1 * r2),
          -c * (r0 + r1 + r2), c};
}

// CheckCrossings checks that f and f - d cross exactly at `roots` (found
// once each, to 1e-10), in 2D and in 3D.
void CheckCrossings(const std::vector<double>& f, const std::vector<double>& d,
                    const std::vector<double>& roots, const char* name) {
  std::vector<double> g(4);
  for (int k = 0; k < 4; ++k) g[k] = f[k] - d[k];
  for (const std::vector<double>& h :
       {std::vector<double>{}, std::vector<double>{0.3, -1.0, 0.5, 0.7}}) {
    std::vector<double> sa, sb;
    const absl::StatusOr<Curve> a = Graph(f, h, sa);
    const absl::StatusOr<Curve> b = Graph(g, h, sb);
    const auto start = std::chrono::steady_clock::now();
    const absl::StatusOr<CurveIntersections> hits =
        IntersectCurves(*a, *b, {.tolerance = 1e-12});
    const double ms = std::chrono::duration<double, std::milli>(
                          std::chrono::steady_clock::now() - start)
                          .count();
    ASSERT_TRUE(hits.ok()) << name << ": " << hits.status();
    ASSERT_EQ(hits->first_parameters.size(), roots.size())
        << name << " in " << (h.empty() ? 2 : 3) << "D";
    EXPECT_TRUE(hits->first_intervals.empty()) << name;
    for (size_t k = 0; k < roots.size(); ++k) {
      EXPECT_NEAR(hits->first_parameters[k], roots[k], 1e-10) << name;
      EXPECT_NEAR(hits->second_parameters[k], roots[k], 1e-10) << name;
    }
    std::printf("%s (%dD): %zu crossings in %.2f ms\n", name, h.empty() ? 2 : 3,
                roots.size(), ms);
  }
}

TEST(IntersectionTest, CurvesCrossingAtKnownParameters) {
  const std::vector<double> f = {0.1, 0.8, -1.5, 0.9};
  CheckCrossings(f, Cubic(2.0, 0.15, 0.5, 0.85), {0.15, 0.5, 0.85},
                 "three crossings");
  CheckCrossings(f, Cubic(1.0, 0.0, 0.5, 1.0), {0.0, 0.5, 1.0},
                 "crossings at the end points");
  CheckCrossings(f, {-0.37e-6, 1e-6, 0.0, 0.0}, {0.37},
                 "near-tangential crossing at 1e-6");
  CheckCrossings(f, {-0.14e-6, 0.9e-6, -1e-6, 0.0}, {0.2, 0.7},
                 "two crossings at 5e-7 angles");
  CheckCrossings(f, {3.5e-7, -1e-6, 1e-6, 0.0}, {}, "no crossing, 1e-7 apart");
}

TEST(IntersectionTest, NonIntersectingPairsGiveNothing) {
  std::vector<double> sa, sb;
  const std::vector<double> f = {0.1, 0.8, -1.5, 0.9};
  const absl::StatusOr<Curve> a = Graph(f, {}, sa);
  const absl::StatusOr<Curve> b = Graph({0.2, 0.8, -0.5, 0.9}, {}, sb);
  const absl::StatusOr<CurveIntersections> hits = IntersectCurves(*a, *b);
  ASSERT_TRUE(hits.ok());
  EXPECT_TRUE(hits->first_parameters.empty());
  EXPECT_TRUE(hits->first_intervals.empty());
  const BSplineCurveData c1 = testing_util::NurbsCircle(1.0, 0.0, 0.0);
  const BSplineCurveData c2 = testing_util::NurbsCircle(0.9, 2.0, 0.1);
  const absl::StatusOr<CurveIntersections> circles = IntersectCurves(
      *BSplineCurve::Create(c1.view()), *BSplineCurve::Create(c2.view()));
  ASSERT_TRUE(circles.ok());
  EXPECT_TRUE(circles->first_parameters.empty());
}

TEST(IntersectionTest, CircleAndLine) {
  const BSplineCurveData circle = testing_util::NurbsCircle(1.0, 0.0, 0.0);
  const std::vector<double> line = {-2, 0.3, 2, 0.3};
  const absl::StatusOr<Curve> a = BSplineCurve::Create(circle.view());
  const absl::StatusOr<Curve> b = BezierCurve::Create({{2, line}, {}});
  const absl::StatusOr<CurveIntersections> hits = IntersectCurves(*a, *b);
  ASSERT_TRUE(hits.ok());
  ASSERT_EQ(hits->first_parameters.size(), 2u);
  const double x = std::sqrt(1 - 0.09);
  const std::vector<double> expected[2] = {{x, 0.3}, {-x, 0.3}};
  for (int k = 0; k < 2; ++k) {
    EXPECT_LE(Distance(CurvePoint(*a, hits->first_parameters[k]), expected[k]),
              1e-12);
    EXPECT_LE(Distance(CurvePoint(*b, hits->second_parameters[k]), expected[k]),
              1e-12);
  }
}

TEST(IntersectionTest, OverlapsComeBackAsOneInterval) {
  std::mt19937_64 rng(9);
  const std::vector<double> net = testing_util::RandomValues(rng, 8);
  const BezierCurveView view{{2, net}, {}};
  const absl::StatusOr<Curve> a = BezierCurve::Create(view);
  const std::vector<double> cuts = {0.2, 0.7};
  const std::vector<BezierCurveData> pieces = *SplitBezierCurve(view, cuts);
  const BezierCurveData& middle = pieces[1];
  // The piece itself, its reverse, and a B-spline copy on [0, 5].
  std::vector<double> reversed;
  for (int k = 3; k >= 0; --k) {
    reversed.insert(reversed.end(), middle.coordinates.begin() + 2 * k,
                    middle.coordinates.begin() + 2 * k + 2);
  }
  const std::vector<double> knots = {0, 0, 0, 0, 5, 5, 5, 5};
  struct Copy {
    absl::StatusOr<Curve> curve;
    double start, end;
  };
  const Copy copies[] = {
      {BezierCurve::Create(middle.view()), 0.0, 1.0},
      {BezierCurve::Create({{2, reversed}, {}}), 1.0, 0.0},
      {BSplineCurve::Create({3, {2, middle.coordinates}, knots, {}}), 0.0,
       5.0}};
  for (const Copy& copy : copies) {
    const absl::StatusOr<CurveIntersections> hits =
        IntersectCurves(*a, *copy.curve);
    ASSERT_TRUE(hits.ok()) << hits.status();
    EXPECT_TRUE(hits->first_parameters.empty());
    ASSERT_EQ(hits->first_intervals.size(), 2u);
    EXPECT_NEAR(hits->first_intervals[0], 0.2, 1e-9);
    EXPECT_NEAR(hits->first_intervals[1], 0.7, 1e-9);
    EXPECT_NEAR(hits->second_intervals[0], copy.start, 1e-9);
    EXPECT_NEAR(hits->second_intervals[1], copy.end, 1e-9);
  }
}

TEST(IntersectionTest, CurveSurfaceTriplesLandOnBoth) {
  // A line through the sphere octant's point (1, 1, 1) / sqrt(3).
  const SurfaceData sphere = testing_util::SpherePatch(1.0);
  const absl::StatusOr<Surface> surface =
      BezierSurface::Create(sphere.bezier_view());
  const std::vector<double> line = {0, 0, 0, 1.5, 1.5, 1.5};
  const absl::StatusOr<Curve> curve = BezierCurve::Create({{3, line}, {}});
  const absl::StatusOr<CurveSurfaceIntersections> hits =
      IntersectCurveSurface(*curve, *surface);
  ASSERT_TRUE(hits.ok()) << hits.status();
  ASSERT_EQ(hits->curve_parameters.size(), 1u);
  EXPECT_NEAR(hits->curve_parameters[0], 1.0 / (1.5 * std::sqrt(3.0)), 1e-12);
  const double c = 1.0 / std::sqrt(3.0);
  EXPECT_LE(Distance(SurfacePoint(*surface, hits->surface_parameters[0],
                                  hits->surface_parameters[1]),
                     {c, c, c}),
            1e-12);

  // A cubic crossing a bicubic graph surface z = F(x, y): the crossings are
  // the sign changes of z(t) - F(x(t), y(t)), bracketed on a dense grid.
  std::mt19937_64 rng(2);
  std::vector<double> net;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      net.insert(net.end(), {i / 3.0, j / 3.0,
                             testing_util::RandomValues(rng, 1, -0.3, 0.3)[0]});
    }
  }
  const absl::StatusOr<Surface> graph =
      BezierSurface::Create({{3, 4, 4, net}, {}});
  // A cubic B-spline whose height swings between -1 and 1 over the patch.
  std::vector<double> path;
  for (int k = 0; k < 8; ++k) {
    path.insert(path.end(), {0.05 + 0.9 * k / 7.0, 0.1 + 0.1 * (k % 3),
                             k % 2 == 0 ? -1.0 : 1.0});
  }
  const std::vector<double> path_knots = {0,   0,   0,   0,   0.2, 0.4,
                                          0.6, 0.8, 1.0, 1.0, 1.0, 1.0};
  const absl::StatusOr<Curve> cubic =
      BSplineCurve::Create({3, {3, path}, path_knots, {}});
  const absl::StatusOr<CurveSurfaceIntersections> crossings =
      IntersectCurveSurface(*cubic, *graph, {.tolerance = 1e-12});
  ASSERT_TRUE(crossings.ok()) << crossings.status();
  auto gap = [&](double t) {
    const std::vector<double> p = CurvePoint(*cubic, t);
    return p[2] - SurfacePoint(*graph, p[0], p[1])[2];
  };
  std::vector<double> roots;
  const int n = 2000;
  for (int k = 0; k < n; ++k) {
    double lo = static_cast<double>(k) / n, hi = static_cast<double>(k + 1) / n;
    if ((gap(lo) < 0) == (gap(hi) < 0)) continue;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      ((gap(mid) < 0) == (gap(lo) < 0) ? lo : hi) = mid;
    }
    roots.push_back(0.5 * (lo + hi));
  }
  ASSERT_GE(roots.size(), 3u);
  ASSERT_EQ(crossings->curve_parameters.size(), roots.size());
  for (size_t k = 0; k < roots.size(); ++k) {
    EXPECT_NEAR(crossings->curve_parameters[k], roots[k], 1e-10);
    const std::vector<double> on_curve =
        CurvePoint(*cubic, crossings->curve_parameters[k]);
    const std::vector<double> on_surface =
        SurfacePoint(*graph, crossings->surface_parameters[2 * k],
                     crossings->surface_parameters[2 * k + 1]);
    EXPECT_LE(Distance(on_curve, on_surface), 1e-12);
  }
}

// The unit square of the plane z = 0 as a bilinear patch: S(u, v) =
// (u, v, 0).
absl::StatusOr<Surface> UnitSquare() {
  static const std::vector<double> net = {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0};
  return BezierSurface::Create({{3, 2, 2, net}, {}});
}

// ExpectCommonPoints checks that every point reported is on both curves:
// A(s) and B(t) within the tolerance, and A(s) the point listed.
void ExpectCommonPoints(const Curve& a, const Curve& b,
                        const CurveIntersections& found, double tolerance) {
  const size_t dim = static_cast<size_t>(found.dimension);
  for (size_t k = 0; k < found.first_parameters.size(); ++k) {
    const std::vector<double> on_a = CurvePoint(a, found.first_parameters[k]);
    const std::vector<double> on_b = CurvePoint(b, found.second_parameters[k]);
    EXPECT_LE(Distance(on_a, on_b), tolerance) << "point " << k;
    const std::vector<double> listed(found.points.begin() + k * dim,
                                     found.points.begin() + (k + 1) * dim);
    EXPECT_LE(Distance(on_a, listed), 1e-12 * (1 + testing_util::MaxAbs(on_a)));
  }
}

// ExpectOneInterval checks that `intervals` is [start, end] to 1e-9.
void ExpectOneInterval(const std::vector<double>& intervals, double start,
                       double end) {
  ASSERT_EQ(intervals.size(), 2u);
  EXPECT_NEAR(intervals[0], start, 1e-9);
  EXPECT_NEAR(intervals[1], end, 1e-9);
}

// A tangency where two Bezier pieces meet is one point: the parabola
// B-spline on knots 0, 0, 0, 1/2, 1, 1, 1 through (-1, 1), (-1/2, 0),
// (1/2, 0), (1, 1) touches the x axis at (0, 0), its parameter 1/2. Near
// there it is (x, x^2) on either piece (x = 2 s - 1 for s >= 1/2), so the
// inputs are within the tolerance e only where |x| <= sqrt(e): the point
// returned is common within e and lies there.
// A segment from (-2, -2) to (2, 0) on the knot span [1e15 + 0.25, 1e15 +
// 0.375] (two ulps of its position; degree 1, then constant), crossed by the
// line x = 0 at the span's middle, 1e15 + 0.3125, which no double is: the
// nearest parameters are the span's ends, 2 away from the crossing. The
// answer refuses, naming the curve, rather than give a parameter whose
// point is not the intersection (a fuzz finding of issue 30); the same
// segment on the span [0.25, 0.375] gives the crossing.
TEST(IntersectionTest, AParameterNoDoubleResolvesIsRefused) {
  const std::vector<double> line = {0, -3, 0, 3};
  const absl::StatusOr<Curve> vertical = BezierCurve::Create({{2, line}, {}});
  const std::vector<double> points = {-2, -2, 2, 0, 2, 0, 2, 0};
  for (const double origin : {1e15, 0.0}) {
    std::vector<double> knots;
    for (const double knot : {0.0, 0.25, 0.375, 0.625, 0.75, 1.0}) {
      knots.push_back(origin + knot);
    }
    const absl::StatusOr<Curve> segment =
        BSplineCurve::Create({1, {2, points}, knots, {}});
    ASSERT_TRUE(segment.ok()) << segment.status();
    const absl::StatusOr<CurveIntersections> found =
        IntersectCurves(*vertical, *segment, {.tolerance = 1e-9});
    if (origin == 0.0) {
      ASSERT_TRUE(found.ok()) << found.status();
      ASSERT_EQ(found->second_parameters.size(), 1u);
      EXPECT_NEAR(found->second_parameters[0], 0.3125, 1e-12);
      ExpectCommonPoints(*vertical, *segment, *found, 1e-9);
      continue;
    }
    ASSERT_FALSE(found.ok());
    EXPECT_EQ(found.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_EQ(FieldPathOf(found.status()), "second") << found.status();
  }
}

// The same class against a surface: the line x = 0, z = 1/2 (y from -3 to
// 3) crosses ShortSpanWall(origin) at v = origin + 0.3125, which at 1e15 no
// double is, so the answer refuses naming the surface; and the segment of
// AParameterNoDoubleResolvesIsRefused (on knots at origin) in the plane
// z = 1/2 crosses the plane x = 0 at its parameter origin + 0.3125, refused
// naming the curve (a fuzz finding: a point at curve 1e10 + 0.5 where the
// inputs were 1 apart). At origin 0 both are found, on both inputs.
TEST(IntersectionTest, ACurveSurfaceParameterNoDoubleResolvesIsRefused) {
  const std::vector<double> line = {0, -3, 0.5, 0, 3, 0.5};
  const absl::StatusOr<Curve> vertical = BezierCurve::Create({{3, line}, {}});
  const std::vector<double> plane_x0 = {0, -3, -1, 0, -3, 1, 0, 3, -1, 0, 3, 1};
  const absl::StatusOr<Surface> plane =
      BezierSurface::Create({{3, 2, 2, plane_x0}, {}});
  const std::vector<double> points = {-2, -2, 0.5, 2, 0, 0.5,
                                      2,  0,  0.5, 2, 0, 0.5};
  for (const double origin : {1e15, 0.0}) {
    const SurfaceData data = testing_util::ShortSpanWall(origin);
    const absl::StatusOr<Surface> wall =
        BSplineSurface::Create(data.bspline_view());
    ASSERT_TRUE(wall.ok()) << wall.status();
    const absl::StatusOr<Curve> segment =
        BSplineCurve::Create({1, {3, points}, data.knots_v, {}});
    ASSERT_TRUE(segment.ok()) << segment.status();
    const std::pair<const Curve*, const Surface*> cases[] = {
        {&*vertical, &*wall}, {&*segment, &*plane}};
    for (const auto& [curve, surface] : cases) {
      const absl::StatusOr<CurveSurfaceIntersections> found =
          IntersectCurveSurface(*curve, *surface, {.tolerance = 1e-9});
      const bool on_wall = surface == &*wall;
      if (origin == 0.0) {
        ASSERT_TRUE(found.ok()) << found.status();
        ASSERT_EQ(found->curve_parameters.size(), 1u);
        EXPECT_NEAR(
            on_wall ? found->surface_parameters[1] : found->curve_parameters[0],
            0.3125, 1e-12);
        const std::vector<double> on_curve =
            CurvePoint(*curve, found->curve_parameters[0]);
        EXPECT_LE(Distance(on_curve,
                           SurfacePoint(*surface, found->surface_parameters[0],
                                        found->surface_parameters[1])),
                  1e-9);
        continue;
      }
      ASSERT_FALSE(found.ok());
      EXPECT_EQ(found.status().code(), absl::StatusCode::kInvalidArgument);
      EXPECT_EQ(FieldPathOf(found.status()), on_wall ? "surface" : "curve")
          << found.status();
    }
  }
}

TEST(IntersectionTest, TangencyOnAKnotIsOnePoint) {
  const std::vector<double> net = {-1, 1, -0.5, 0, 0.5, 0, 1, 1};
  const std::vector<double> knots = {0, 0, 0, 0.5, 1, 1, 1};
  const absl::StatusOr<Curve> parabola =
      BSplineCurve::Create({2, {2, net}, knots, {}});
  ASSERT_TRUE(parabola.ok()) << parabola.status();
  for (const double shift : {0.0, 0.3, -0.7}) {
    // The line y = 0 from x = -2 to 2, and one shifted along itself.
    const std::vector<double> line = {-2 + shift, 0, 2 + shift, 0};
    const absl::StatusOr<Curve> axis = BezierCurve::Create({{2, line}, {}});
    for (const double tolerance : {1e-6, 1e-9, 1e-12}) {
      for (const bool swap : {false, true}) {
        const Curve& a = swap ? *axis : *parabola;
        const Curve& b = swap ? *parabola : *axis;
        const absl::StatusOr<CurveIntersections> found =
            IntersectCurves(a, b, {.tolerance = tolerance});
        ASSERT_TRUE(found.ok()) << found.status();
        ASSERT_EQ(found->first_parameters.size(), 1u)
            << "tolerance " << tolerance << " shift " << shift;
        EXPECT_TRUE(found->first_intervals.empty());
        ExpectCommonPoints(a, b, *found, tolerance);
        EXPECT_LE(std::abs(found->points[0]), std::sqrt(tolerance) * 1.01);
      }
    }
  }
  // The same tangency against a surface: the parabola lifted to z = y - 0
  // in the plane y = 1/2 would be a crossing; instead the plane curve
  // (x, 1/2, x^2) over the unit square's plane z = 0, its knot at x = 1/2.
  const std::vector<double> lifted = {0,    0.5, 1, 0.25, 0.5, 0,
                                      0.75, 0.5, 0, 1,    0.5, 1};
  const absl::StatusOr<Curve> touching =
      BSplineCurve::Create({2, {3, lifted}, knots, {}});
  const absl::StatusOr<Surface> square = UnitSquare();
  const absl::StatusOr<CurveSurfaceIntersections> touch =
      IntersectCurveSurface(*touching, *square, {.tolerance = 1e-9});
  ASSERT_TRUE(touch.ok()) << touch.status();
  ASSERT_EQ(touch->curve_parameters.size(), 1u);
  EXPECT_TRUE(touch->curve_intervals.empty());
  const std::vector<double> on_curve =
      CurvePoint(*touching, touch->curve_parameters[0]);
  EXPECT_LE(
      Distance(on_curve, SurfacePoint(*square, touch->surface_parameters[0],
                                      touch->surface_parameters[1])),
      1e-9);
}

// A tolerance below 2^-48 of the largest coordinate is refused at once,
// naming it; one just above that still finds a crossing exactly: the
// vertical line through (1/4, 1/2) meets the unit square at its parameter
// 1/2, and the circle crosses the x axis at (+-1, 0).
TEST(IntersectionTest, ToleranceBelowTheResolutionIsRefused) {
  const BSplineCurveData circle_data = testing_util::NurbsCircle(1.0);
  const absl::StatusOr<Curve> circle = BSplineCurve::Create(circle_data.view());
  for (const double tolerance : {5e-324, 1e-17, 3e-15}) {
    const absl::Status status =
        IntersectCurves(*circle, *circle, {.tolerance = tolerance}).status();
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << status;
    EXPECT_EQ(FieldPathOf(status), "tolerance");
  }
  const std::vector<double> vertical = {0.25, 0.5, -1, 0.25, 0.5, 1};
  const absl::StatusOr<Curve> line = BezierCurve::Create({{3, vertical}, {}});
  const absl::StatusOr<Surface> square = UnitSquare();
  const absl::Status fine =
      IntersectCurveSurface(*line, *square, {.tolerance = 1e-17}).status();
  EXPECT_EQ(fine.code(), absl::StatusCode::kInvalidArgument) << fine;
  EXPECT_EQ(FieldPathOf(fine), "tolerance");
  const double floor = std::ldexp(1.0, -47);  // twice the resolution at 1
  const absl::StatusOr<CurveSurfaceIntersections> hit =
      IntersectCurveSurface(*line, *square, {.tolerance = floor});
  ASSERT_TRUE(hit.ok()) << hit.status();
  ASSERT_EQ(hit->curve_parameters.size(), 1u);
  EXPECT_NEAR(hit->curve_parameters[0], 0.5, 4 * floor);
  EXPECT_NEAR(hit->surface_parameters[0], 0.25, 4 * floor);
  EXPECT_NEAR(hit->surface_parameters[1], 0.5, 4 * floor);
  const std::vector<double> axis_points = {-2, 0, 2, 0};
  const absl::StatusOr<Curve> axis =
      BezierCurve::Create({{2, axis_points}, {}});
  const absl::StatusOr<CurveIntersections> crossings =
      IntersectCurves(*circle, *axis, {.tolerance = floor});
  ASSERT_TRUE(crossings.ok()) << crossings.status();
  ASSERT_EQ(crossings->first_parameters.size(), 2u);
  ExpectCommonPoints(*circle, *axis, *crossings, floor);
}

// Scaling every coordinate and the tolerance by 2^k changes no parameter:
// the circle of radius 2^k crosses the line y = 0.3 2^k where the unit
// circle crosses y = 0.3, for k far past where squared lengths overflow or
// underflow.
TEST(IntersectionTest, AnswersDoNotDependOnTheScale) {
  for (const double scale : {1.0, 0x1p600, 0x1p-600, 0x1p1000, 0x1p-1000}) {
    const BSplineCurveData circle_data = testing_util::NurbsCircle(scale);
    const absl::StatusOr<Curve> circle =
        BSplineCurve::Create(circle_data.view());
    const std::vector<double> line = {-2 * scale, 0.3 * scale, 2 * scale,
                                      0.3 * scale};
    const absl::StatusOr<Curve> chord = BezierCurve::Create({{2, line}, {}});
    const absl::StatusOr<CurveIntersections> found = IntersectCurves(
        *circle, *chord,
        {.tolerance = 1e-9 * scale, .separation = 1e-7 * scale});
    ASSERT_TRUE(found.ok()) << scale << ": " << found.status();
    ASSERT_EQ(found->first_parameters.size(), 2u) << scale;
    const double x = std::sqrt(1 - 0.09) * scale;
    EXPECT_NEAR(found->points[0] / scale, x / scale, 1e-12);
    EXPECT_NEAR(found->points[2] / scale, -x / scale, 1e-12);
    EXPECT_NEAR(found->points[1] / scale, 0.3, 1e-12);
    // The line through the unit square's middle, vertically, scaled.
    const std::vector<double> square_net = {0,     0, 0, 0,     scale, 0,
                                            scale, 0, 0, scale, scale, 0};
    const absl::StatusOr<Surface> square =
        BezierSurface::Create({{3, 2, 2, square_net}, {}});
    const std::vector<double> vertical = {0.25 * scale, 0.5 * scale, -scale,
                                          0.25 * scale, 0.5 * scale, scale};
    const absl::StatusOr<Curve> through =
        BezierCurve::Create({{3, vertical}, {}});
    const absl::StatusOr<CurveSurfaceIntersections> hit =
        IntersectCurveSurface(*through, *square, {.tolerance = 1e-9 * scale});
    ASSERT_TRUE(hit.ok()) << scale << ": " << hit.status();
    ASSERT_EQ(hit->curve_parameters.size(), 1u) << scale;
    EXPECT_NEAR(hit->curve_parameters[0], 0.5, 1e-12);
  }
}

// A segment lying in the unit square is an overlap: the whole of it, or the
// part over the square, [1/4, 3/4], of one reaching past both sides (an
// overlap ends where one input does); and so is an arc lying in a sphere.
TEST(IntersectionTest, CurveLyingInASurfaceIsAnOverlap) {
  const absl::StatusOr<Surface> square = UnitSquare();
  struct Case {
    std::vector<double> points;
    double start, end;
  };
  const Case cases[] = {{{0.1, 0.2, 0, 0.8, 0.7, 0}, 0.0, 1.0},
                        {{-0.5, 0.5, 0, 1.5, 0.5, 0}, 0.25, 0.75}};
  for (const double tolerance : {1e-3, 1e-9}) {
    for (size_t c = 0; c < 2; ++c) {
      const absl::StatusOr<Curve> segment =
          BezierCurve::Create({{3, cases[c].points}, {}});
      const absl::StatusOr<CurveSurfaceIntersections> found =
          IntersectCurveSurface(*segment, *square, {.tolerance = tolerance});
      ASSERT_TRUE(found.ok()) << found.status();
      EXPECT_TRUE(found->curve_parameters.empty())
          << found->curve_parameters.size() << " points, case " << c;
      ExpectOneInterval(found->curve_intervals, cases[c].start, cases[c].end);
    }
  }
  // On the sphere patch of radius 2: its equator (a boundary edge), a
  // meridian and the circle of latitude z = 1, as rational quadratic arcs.
  const SurfaceData sphere_data = testing_util::SpherePatch(2.0);
  const absl::StatusOr<Surface> sphere =
      BezierSurface::Create(sphere_data.bezier_view());
  const double r = std::sqrt(3.0);
  const std::vector<double> weights = {1, std::sqrt(0.5), 1};
  const std::vector<double> arcs[] = {{2, 0, 0, 2, 2, 0, 0, 2, 0},
                                      {2, 0, 0, 2, 0, 2, 0, 0, 2},
                                      {r, 0, 1, r, r, 1, 0, r, 1}};
  for (const std::vector<double>& arc : arcs) {
    const absl::StatusOr<Curve> curve =
        BezierCurve::Create({{3, arc}, weights});
    for (const double tolerance : {1e-6, 1e-12}) {
      const absl::StatusOr<CurveSurfaceIntersections> found =
          IntersectCurveSurface(*curve, *sphere, {.tolerance = tolerance});
      ASSERT_TRUE(found.ok()) << found.status();
      EXPECT_TRUE(found->curve_parameters.empty());
      ExpectOneInterval(found->curve_intervals, 0.0, 1.0);
    }
  }
}

// A contact of high order: the Bezier curve with control points
// (i / n, 1/2, (-1)^i), i = 0..n, is (t, 1/2, (1 - 2t)^n), within e of the
// plane z = 0 where |1 - 2t| <= e^(1/n), tangent to it there within 1e-8
// rad along a long stretch: an overlap over that interval, found with
// bounded work. The same against the x axis in the plane.
TEST(IntersectionTest, HighOrderContactIsOneOverlap) {
  const absl::StatusOr<Surface> square = UnitSquare();
  for (const int n : {16, 48}) {
    std::vector<double> net3, net2;
    for (int i = 0; i <= n; ++i) {
      const double z = i % 2 == 0 ? 1.0 : -1.0;
      net3.insert(net3.end(), {static_cast<double>(i) / n, 0.5, z});
      net2.insert(net2.end(), {static_cast<double>(i) / n, z});
    }
    const double tolerance = 1e-9;
    const double half = 0.5 * std::pow(tolerance, 1.0 / n);
    const absl::StatusOr<Curve> curve = BezierCurve::Create({{3, net3}, {}});
    const absl::StatusOr<CurveSurfaceIntersections> found =
        IntersectCurveSurface(*curve, *square, {.tolerance = tolerance});
    ASSERT_TRUE(found.ok()) << "degree " << n << ": " << found.status();
    EXPECT_TRUE(found->curve_parameters.empty());
    ExpectOneInterval(found->curve_intervals, 0.5 - half, 0.5 + half);
    const absl::StatusOr<Curve> graph = BezierCurve::Create({{2, net2}, {}});
    const std::vector<double> axis_points = {-1, 0, 2, 0};
    const absl::StatusOr<Curve> axis =
        BezierCurve::Create({{2, axis_points}, {}});
    const absl::StatusOr<CurveIntersections> along =
        IntersectCurves(*graph, *axis, {.tolerance = tolerance});
    ASSERT_TRUE(along.ok()) << "degree " << n << ": " << along.status();
    EXPECT_TRUE(along->first_parameters.empty());
    ExpectOneInterval(along->first_intervals, 0.5 - half, 0.5 + half);
    // x = t on the graph is -1 + 3 t' on the axis.
    ExpectOneInterval(along->second_intervals, (1.5 - half) / 3,
                      (1.5 + half) / 3);
  }
}

// The work is bounded by max_work, named when it runs out.
TEST(IntersectionTest, WorkStopsAtItsLimit) {
  std::vector<double> a_net, b_net;
  for (int i = 0; i < 200; ++i) {
    a_net.insert(a_net.end(), {std::sin(i * 0.37), 2 * std::sin(i * 0.74)});
    b_net.insert(b_net.end(), {std::cos(i * 0.41), 2 * std::sin(i * 0.53)});
  }
  std::vector<double> knots;
  for (int k = 0; k < 204; ++k) knots.push_back(std::clamp(k - 3, 0, 197));
  const absl::StatusOr<Curve> a =
      BSplineCurve::Create({3, {2, a_net}, knots, {}});
  const absl::StatusOr<Curve> b =
      BSplineCurve::Create({3, {2, b_net}, knots, {}});
  ASSERT_TRUE(a.ok() && b.ok());
  const absl::StatusOr<CurveIntersections> all = IntersectCurves(
      *a, *b, {.max_results = 1 << 16, .max_work = uint64_t{1} << 40});
  ASSERT_TRUE(all.ok()) << all.status();
  EXPECT_GT(all->first_parameters.size(), 100u);
  ExpectCommonPoints(*a, *b, *all, 1e-9);
  const absl::Status short_of_work =
      IntersectCurves(*a, *b, {.max_results = 1 << 16, .max_work = 100'000})
          .status();
  EXPECT_EQ(short_of_work.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(FieldPathOf(short_of_work), "max_work");
}

TEST(IntersectionTest, ErrorsNameTheirField) {
  const std::vector<double> line2 = {0, 0, 1, 1};
  const std::vector<double> line3 = {0, 0, 0, 1, 1, 1};
  const absl::StatusOr<Curve> a = BezierCurve::Create({{2, line2}, {}});
  const absl::StatusOr<Curve> b = BezierCurve::Create({{3, line3}, {}});
  EXPECT_EQ(FieldPathOf(IntersectCurves(*a, *b).status()), "second.dimension");
  EXPECT_EQ(FieldPathOf(IntersectCurves(*a, *a, {.tolerance = -1}).status()),
            "tolerance");
  // A zigzag crossing a line 5 times, with room for 3.
  const std::vector<double> zigzag = {0, -1, 1, 1, 2, -1, 3, 1, 4, -1, 5, 1};
  const std::vector<double> knots = {0, 0, 1, 2, 3, 4, 5, 5};
  const std::vector<double> axis = {-1, 0, 6, 0};
  const absl::StatusOr<Curve> polyline =
      BSplineCurve::Create({1, {2, zigzag}, knots, {}});
  const absl::StatusOr<Curve> x_axis = BezierCurve::Create({{2, axis}, {}});
  const absl::StatusOr<CurveIntersections> all =
      IntersectCurves(*polyline, *x_axis);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->first_parameters.size(), 5u);
  const absl::Status over =
      IntersectCurves(*polyline, *x_axis, {.max_results = 3}).status();
  EXPECT_EQ(over.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(FieldPathOf(over), "max_results");
  CancellationToken token;
  token.Cancel();
  EXPECT_EQ(IntersectCurves(*polyline, *x_axis, {}, &token).status().code(),
            absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace freeform
