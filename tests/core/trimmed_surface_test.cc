// Trimmed faces (trimmed_surface.h) against the mathematics: areas of
// planes, cylinders and spheres in closed form, point classification at
// known distances from circles and against brute-force ray casting, and
// every validation rule with its field path.
#include "freeform/core/trimmed_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "freeform/core/arc_length.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/status.h"
#include "shapes.h"
#include "test_util.h"
#include "trim_shapes.h"

namespace freeform {
namespace {

using testing_util::NurbsCircle;
using testing_util::NurbsSphere;
using trim_testing::BilinearPlane;
using trim_testing::BrokenLine;
using trim_testing::ClockwiseCircle;
using trim_testing::LoopOf;
using trim_testing::Square;

constexpr double kPi = std::numbers::pi;

absl::StatusOr<TrimmedSurface> MakeFace(const Surface& surface,
                                        std::optional<TrimLoop> outer,
                                        std::vector<TrimLoop> holes,
                                        double tolerance = 1e-9) {
  return TrimmedSurface::Create({.surface = surface,
                                 .outer = std::move(outer),
                                 .holes = std::move(holes)},
                                tolerance);
}

PointLocation Where(const TrimmedSurface& face, double u, double v,
                    double tolerance) {
  const double uv[] = {u, v};
  absl::StatusOr<std::vector<PointLocation>> at =
      ClassifyPoints(face, uv, tolerance);
  EXPECT_TRUE(at.ok()) << at.status();
  return at.ok() ? (*at)[0] : PointLocation::kOnBoundary;
}

// The failure's field path.
std::string PathOf(const absl::StatusOr<TrimmedSurface>& face) {
  EXPECT_FALSE(face.ok());
  EXPECT_EQ(face.status().code(), absl::StatusCode::kInvalidArgument)
      << face.status();
  return FieldPathOf(face.status()).value_or("<none>");
}

TEST(TrimmedSurface, PlaneSquareWithCircularHoleHasAreaOneMinusPiRSquared) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  for (const double r : {0.25, 0.1, 0.4999}) {
    const BSplineCurveData hole = ClockwiseCircle(r, 0.5, 0.5);
    absl::StatusOr<TrimmedSurface> face =
        MakeFace(surface, std::nullopt, {LoopOf(hole)});
    ASSERT_TRUE(face.ok()) << face.status();
    absl::StatusOr<FaceAreaResult> area = FaceArea(*face, 1e-13);
    ASSERT_TRUE(area.ok()) << area.status();
    const double exact = 1.0 - kPi * r * r;
    EXPECT_NEAR(area->area, exact, 1e-12 * exact) << "r = " << r;
    EXPECT_LE(area->error_bound, 1e-13);
  }
}

TEST(TrimmedSurface, ScaledPlaneAreaIsTheDensityTimesTheDomainArea) {
  // S(u, v) = (3u, 2v + u, 0): |S_u x S_v| = 6 everywhere.
  SurfaceData plane = BilinearPlane();
  plane.coordinates = {0, 0, 0, 0, 2, 0, 3, 1, 0, 3, 3, 0};
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  const BSplineCurveData hole = ClockwiseCircle(0.3, 0.4, 0.6);
  const std::vector<BezierCurveData> outer = Square(0.05, 0.02, 0.95, 0.97);
  absl::StatusOr<TrimmedSurface> face =
      MakeFace(surface, LoopOf(outer), {LoopOf(hole)});
  ASSERT_TRUE(face.ok()) << face.status();
  absl::StatusOr<FaceAreaResult> area = FaceArea(*face, 1e-12);
  ASSERT_TRUE(area.ok()) << area.status();
  const double exact = 6.0 * (0.9 * 0.95 - kPi * 0.09);
  EXPECT_NEAR(area->area, exact, 1e-12 * exact);
}

TEST(TrimmedSurface, PointsAtKnownDistancesFromTheHoleAreClassified) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  const double r = 0.25;
  const BSplineCurveData hole = ClockwiseCircle(r, 0.5, 0.5);
  absl::StatusOr<TrimmedSurface> face =
      MakeFace(surface, std::nullopt, {LoopOf(hole)});
  ASSERT_TRUE(face.ok()) << face.status();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(0.0, 2 * kPi);
  for (int trial = 0; trial < 200; ++trial) {
    const double theta = angle(rng);
    const auto at = [&](double offset) {
      return std::array<double, 2>{0.5 + (r + offset) * std::cos(theta),
                                   0.5 + (r + offset) * std::sin(theta)};
    };
    for (const auto& [offset, tolerance, expected] :
         {std::tuple{1e-9, 1e-12, PointLocation::kInside},
          {-1e-9, 1e-12, PointLocation::kOutside},
          {1e-3, 1e-9, PointLocation::kInside},
          {-1e-3, 1e-9, PointLocation::kOutside},
          {0.2, 1e-9, PointLocation::kInside},
          {-0.2, 1e-9, PointLocation::kOutside},
          {5e-10, 1e-9, PointLocation::kOnBoundary},
          {-5e-10, 1e-9, PointLocation::kOnBoundary},
          {0.0, 1e-12, PointLocation::kOnBoundary},
          {2e-9, 1e-9, PointLocation::kInside}}) {
      const std::array<double, 2> p = at(offset);
      EXPECT_EQ(Where(*face, p[0], p[1], tolerance), expected)
          << "theta " << theta << " offset " << offset;
    }
  }
  // The parameter square is the outer boundary.
  EXPECT_EQ(Where(*face, 0.0, 0.1, 1e-9), PointLocation::kOnBoundary);
  EXPECT_EQ(Where(*face, 1.0 + 1e-10, 0.9, 1e-9), PointLocation::kOnBoundary);
  EXPECT_EQ(Where(*face, 1e-8, 0.1, 1e-9), PointLocation::kInside);
  EXPECT_EQ(Where(*face, -1e-8, 0.1, 1e-9), PointLocation::kOutside);
  EXPECT_EQ(Where(*face, 3.0, 0.5, 1e-9), PointLocation::kOutside);
}

// The cylinder of radius r and height h: u along the axis (z = h u), v
// around it (the nine-point NURBS circle).
SurfaceData Cylinder(double r, double h) {
  return testing_util::Revolve({{r, 0, 1}, {r, h / 2, 1}, {r, h, 1}},
                               {0, 0, 0, 1, 1, 1});
}

// Angle returns the polar angle of the cylinder's point at v and its
// derivative, from the surface's point and S_v.
std::pair<double, double> Angle(const Surface& cylinder, double v) {
  const double uv[] = {0.5, v};
  std::vector<double> point(3), su(3), sv(3);
  const absl::Span<double> output[] = {absl::MakeSpan(point),
                                       absl::MakeSpan(su), absl::MakeSpan(sv)};
  EXPECT_TRUE(
      EvaluateSurface(cylinder, SurfaceSamples::Pairs(uv), output, {}).ok());
  const double x = point[0], y = point[1];
  return {std::atan2(y, x), (x * sv[1] - y * sv[0]) / (x * x + y * y)};
}

TEST(TrimmedSurface, CylinderWindowWithARoundHoleHasTheClosedFormArea) {
  const double r = 1.5, h = 2.0;
  const SurfaceData data = Cylinder(r, h);
  const Surface cylinder = *BSplineSurface::Create(data.bspline_view());
  const double u0 = 0.1, u1 = 0.9, v0 = 0.02, v1 = 0.23;
  const std::vector<BezierCurveData> window = Square(u0, v0, u1, v1);
  const double uc = 0.45, vc = 0.125, rho = 0.06;
  const BSplineCurveData hole = ClockwiseCircle(rho, uc, vc);
  absl::StatusOr<TrimmedSurface> face =
      MakeFace(cylinder, LoopOf(window), {LoopOf(hole)});
  ASSERT_TRUE(face.ok()) << face.status();
  const double tolerance = 1e-10;
  absl::StatusOr<FaceAreaResult> area = FaceArea(*face, tolerance);
  ASSERT_TRUE(area.ok()) << area.status();
  // The window: r (theta(v1) - theta(v0)) h (u1 - u0). The hole: the
  // density h r theta'(v) over the disk, with v = vc + rho sin(phi):
  // h r integral of theta'(v) 2 rho^2 cos^2(phi) over [-pi/2, pi/2]
  // (Gauss-Legendre, 64 points; theta' is smooth inside one span).
  const double window_area =
      r * (Angle(cylinder, v1).first - Angle(cylinder, v0).first) * h *
      (u1 - u0);
  std::vector<double> nodes(64), weights(64);
  GaussLegendreRule(64, absl::MakeSpan(nodes), absl::MakeSpan(weights));
  double hole_area = 0.0;
  for (int k = 0; k < 64; ++k) {
    const double phi = 0.5 * kPi * nodes[k];
    hole_area += weights[k] * 0.5 * kPi *
                 Angle(cylinder, vc + rho * std::sin(phi)).second * 2 * rho *
                 rho * std::cos(phi) * std::cos(phi);
  }
  hole_area *= h * r;
  EXPECT_NEAR(area->area, window_area - hole_area, tolerance + 1e-13);
  EXPECT_LE(area->error_bound, tolerance);
}

TEST(TrimmedSurface, NurbsSphereHasAreaFourPiRSquared) {
  const double radius = 2.0;
  const SurfaceData data = NurbsSphere(radius);
  const Surface sphere = *BSplineSurface::Create(data.bspline_view());
  absl::StatusOr<TrimmedSurface> face = MakeFace(sphere, std::nullopt, {});
  ASSERT_TRUE(face.ok()) << face.status();
  for (const double tolerance : {1e-4, 1e-8, 1e-11}) {
    absl::StatusOr<FaceAreaResult> area = FaceArea(*face, tolerance);
    ASSERT_TRUE(area.ok()) << area.status();
    EXPECT_NEAR(area->area, 4 * kPi * radius * radius, tolerance);
    EXPECT_LE(area->error_bound, tolerance);
  }
}

TEST(TrimmedSurface, AHoleTangentToAKnotLineKeepsTheExactArea) {
  // The plane as a bilinear B-spline with a knot at u = 0.5 and v = 0.5;
  // the hole touches both knot lines.
  const SurfaceData plane = trim_testing::KnottedPlane();
  const Surface surface = *BSplineSurface::Create(plane.bspline_view());
  const double r = 0.2;
  const BSplineCurveData hole = ClockwiseCircle(r, 0.3, 0.3);
  absl::StatusOr<TrimmedSurface> face =
      MakeFace(surface, std::nullopt, {LoopOf(hole)});
  ASSERT_TRUE(face.ok()) << face.status();
  absl::StatusOr<FaceAreaResult> area = FaceArea(*face, 1e-13);
  ASSERT_TRUE(area.ok()) << area.status();
  EXPECT_NEAR(area->area, 1.0 - kPi * r * r, 1e-12);
  EXPECT_EQ(Where(*face, 0.5, 0.3, 1e-12), PointLocation::kOnBoundary);
  EXPECT_EQ(Where(*face, 0.5 + 1e-9, 0.3, 1e-12), PointLocation::kInside);
  EXPECT_EQ(Where(*face, 0.5 - 1e-9, 0.3, 1e-12), PointLocation::kOutside);
}

TEST(TrimmedSurface, TrimsTouchingTheDomainBoundaryAreValid) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  // The outer loop is the parameter square itself.
  const std::vector<BezierCurveData> outer = Square(0, 0, 1, 1);
  const BSplineCurveData inner = ClockwiseCircle(0.2, 0.6, 0.5);
  absl::StatusOr<TrimmedSurface> square =
      MakeFace(surface, LoopOf(outer), {LoopOf(inner)});
  ASSERT_TRUE(square.ok()) << square.status();
  EXPECT_EQ(Where(*square, 0.0, 0.5, 1e-9), PointLocation::kOnBoundary);
  // Without an outer loop a hole may touch the square: this one, turned so
  // that its control points poke out of the square, touches u = 0.
  const BSplineCurveData hole =
      trim_testing::Turned(ClockwiseCircle(0.25, 0.25, 0.5), 0.25, 0.5, 0.3);
  absl::StatusOr<TrimmedSurface> face =
      MakeFace(surface, std::nullopt, {LoopOf(hole)});
  ASSERT_TRUE(face.ok()) << face.status();
  absl::StatusOr<FaceAreaResult> area = FaceArea(*face, 1e-13);
  ASSERT_TRUE(area.ok()) << area.status();
  EXPECT_NEAR(area->area, 1.0 - kPi * 0.0625, 1e-12);
  EXPECT_EQ(Where(*face, 0.0, 0.5, 1e-12), PointLocation::kOnBoundary);
  EXPECT_EQ(Where(*face, 1e-6, 0.5, 1e-12), PointLocation::kOutside);
  EXPECT_EQ(Where(*face, 1e-6, 0.2, 1e-12), PointLocation::kInside);
}

TEST(TrimmedSurface, AHoleAMicronFromTheOuterLoopIsValid) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  const std::vector<BezierCurveData> outer = Square(0.1, 0.1, 0.9, 0.9);
  const double r = 0.4 - 1e-6;
  const BSplineCurveData hole = ClockwiseCircle(r, 0.5, 0.5);
  absl::StatusOr<TrimmedSurface> face =
      MakeFace(surface, LoopOf(outer), {LoopOf(hole)});
  ASSERT_TRUE(face.ok()) << face.status();
  absl::StatusOr<FaceAreaResult> area = FaceArea(*face, 1e-13);
  ASSERT_TRUE(area.ok()) << area.status();
  EXPECT_NEAR(area->area, 0.64 - kPi * r * r, 1e-12);
  // Between the two, 5e-7 from each.
  EXPECT_EQ(Where(*face, 0.1 + 5e-7, 0.5, 1e-9), PointLocation::kInside);
}

TEST(TrimmedSurface, ZeroLengthPiecesAreSkipped) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  // A square with a zero-length curve at one corner.
  std::vector<BezierCurveData> outer = Square(0.2, 0.2, 0.8, 0.8);
  outer.insert(outer.begin() + 2, BrokenLine({{0.8, 0.8}, {0.8, 0.8}})[0]);
  absl::StatusOr<TrimmedSurface> face = MakeFace(surface, LoopOf(outer), {});
  ASSERT_TRUE(face.ok()) << face.status();
  absl::StatusOr<FaceAreaResult> area = FaceArea(*face, 1e-13);
  ASSERT_TRUE(area.ok()) << area.status();
  EXPECT_NEAR(area->area, 0.36, 1e-14);
}

TEST(TrimmedSurfaceValidation, BadLoopsAreNamedByPath) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  const std::vector<BezierCurveData> square = Square(0.1, 0.1, 0.9, 0.9);
  const BSplineCurveData hole = ClockwiseCircle(0.1, 0.3, 0.3);
  // Open: the third edge stops 1e-3 short of the fourth.
  std::vector<BezierCurveData> open = square;
  open[2].coordinates[2] += 1e-3;
  EXPECT_EQ(PathOf(MakeFace(surface, LoopOf(open), {})), "outer.curves[3]");
  // Crossing: a second hole overlapping the first.
  const BSplineCurveData crossing = ClockwiseCircle(0.1, 0.35, 0.3);
  EXPECT_EQ(PathOf(MakeFace(surface, LoopOf(square),
                            {LoopOf(hole), LoopOf(crossing)})),
            "holes[1].curves[0]");
  // A hole running counter-clockwise.
  const BSplineCurveData counter = NurbsCircle(0.1, 0.3, 0.3);
  EXPECT_EQ(PathOf(MakeFace(surface, LoopOf(square), {LoopOf(counter)})),
            "holes[0]");
  // The outer loop running clockwise.
  const std::vector<BezierCurveData> clockwise = trim_testing::Reversed(square);
  EXPECT_EQ(PathOf(MakeFace(surface, LoopOf(clockwise), {})), "outer");
  // A trim outside the domain.
  const BSplineCurveData outside = ClockwiseCircle(0.2, 0.9, 0.5);
  EXPECT_EQ(PathOf(MakeFace(surface, std::nullopt, {LoopOf(outside)})),
            "holes[0].curves[0]");
  // A hole outside the outer loop.
  const std::vector<BezierCurveData> small = Square(0.1, 0.1, 0.5, 0.5);
  const BSplineCurveData far = ClockwiseCircle(0.1, 0.75, 0.75);
  EXPECT_EQ(PathOf(MakeFace(surface, LoopOf(small), {LoopOf(far)})),
            "holes[0]");
  // A hole inside another.
  const BSplineCurveData big = ClockwiseCircle(0.3, 0.5, 0.5);
  const BSplineCurveData inner = ClockwiseCircle(0.1, 0.5, 0.5);
  absl::StatusOr<TrimmedSurface> nested =
      MakeFace(surface, std::nullopt, {LoopOf(big), LoopOf(inner)});
  EXPECT_EQ(PathOf(nested), "holes[1]");
  EXPECT_NE(nested.status().message().find("holes[0]"), std::string::npos)
      << nested.status();
  // A loop crossing itself: a bow tie.
  const std::vector<BezierCurveData> bow =
      BrokenLine({{0.2, 0.2}, {0.8, 0.8}, {0.8, 0.2}, {0.2, 0.8}, {0.2, 0.2}});
  EXPECT_EQ(PathOf(MakeFace(surface, LoopOf(bow), {})), "outer.curves[2]");
  // A 3D trim curve.
  const BezierCurveData spatial{
      .dimension = 3, .coordinates = {0.2, 0.2, 0, 0.8, 0.2, 0}, .weights = {}};
  std::vector<BezierCurveData> with_spatial = square;
  with_spatial[0] = spatial;
  EXPECT_EQ(PathOf(MakeFace(surface, LoopOf(with_spatial), {})),
            "outer.curves[0]");
  // A loop without curves, and a bad tolerance.
  EXPECT_EQ(PathOf(MakeFace(surface, TrimLoop{}, {})), "outer.curves");
  EXPECT_EQ(PathOf(MakeFace(surface, LoopOf(square), {}, 0.0)), "tolerance");
}

TEST(TrimmedSurfaceValidation, ACancelledTokenStopsCreate) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  const BSplineCurveData hole = ClockwiseCircle(0.1, 0.3, 0.3);
  CancellationToken cancel;
  cancel.Cancel();
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(
      {.surface = surface, .outer = std::nullopt, .holes = {LoopOf(hole)}},
      1e-9, &cancel);
  EXPECT_EQ(face.status().code(), absl::StatusCode::kCancelled);
}

// EvenOdd classifies p against dense samples of every loop by ray casting.
bool EvenOdd(const std::vector<std::vector<double>>& polygons, double u,
             double v) {
  bool inside = false;
  for (const std::vector<double>& p : polygons) {
    const size_t n = p.size() / 2;
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
      const double ui = p[2 * i], vi = p[2 * i + 1];
      const double uj = p[2 * j], vj = p[2 * j + 1];
      if ((vi > v) != (vj > v) && u < (uj - ui) * (v - vi) / (vj - vi) + ui) {
        inside = !inside;
      }
    }
  }
  return inside;
}

double DistanceToSamples(const std::vector<std::vector<double>>& polygons,
                         double u, double v) {
  double best = INFINITY;
  for (const std::vector<double>& p : polygons) {
    for (size_t i = 0; i + 1 < p.size(); i += 2) {
      best = std::min(best, std::hypot(p[i] - u, p[i + 1] - v));
    }
  }
  return best;
}

TEST(TrimmedSurface, ClassificationAgreesWithBruteForceRayCasting) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  const BSplineCurveData flower = trim_testing::Flower(0.5, 0.5, 0.35, 0.08, 5);
  const BSplineCurveData hole1 = ClockwiseCircle(0.1, 0.5, 0.5);
  const BSplineCurveData hole2 = ClockwiseCircle(0.03, 0.68, 0.5);
  absl::StatusOr<TrimmedSurface> face =
      MakeFace(surface, LoopOf(flower), {LoopOf(hole1), LoopOf(hole2)});
  ASSERT_TRUE(face.ok()) << face.status();
  std::vector<std::vector<double>> polygons;
  for (const BSplineCurveData* loop : {&flower, &hole1, &hole2}) {
    const Curve curve = *BSplineCurve::Create(loop->view());
    polygons.push_back(testing_util::CurvePoints(
        curve, testing_util::EvenlySpaced(0.0, 1.0, 4000)));
  }
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coordinate(-0.05, 1.05);
  std::vector<double> uv;
  for (int k = 0; k < 4000; ++k) {
    uv.push_back(coordinate(rng));
    uv.push_back(coordinate(rng));
  }
  absl::StatusOr<std::vector<PointLocation>> at =
      ClassifyPoints(*face, uv, 1e-9);
  ASSERT_TRUE(at.ok()) << at.status();
  int compared = 0;
  for (size_t k = 0; k < at->size(); ++k) {
    const double u = uv[2 * k], v = uv[2 * k + 1];
    if (DistanceToSamples(polygons, u, v) < 1e-3) continue;
    const bool inside =
        u >= 0 && u <= 1 && v >= 0 && v <= 1 && EvenOdd(polygons, u, v);
    EXPECT_EQ((*at)[k],
              inside ? PointLocation::kInside : PointLocation::kOutside)
        << u << ", " << v;
    ++compared;
  }
  EXPECT_GT(compared, 3000);
}

// ShoelaceArea returns the signed area of the polygon through dense
// samples of a closed curve.
double ShoelaceArea(const Curve& curve, int samples) {
  const ParameterDomain domain = DomainOf(curve);
  const std::vector<double> p = testing_util::CurvePoints(
      curve, testing_util::EvenlySpaced(domain.start, domain.end, samples));
  double area = 0.0;
  for (size_t i = 0; i + 3 < p.size(); i += 2) {
    area += p[i] * p[i + 3] - p[i + 2] * p[i + 1];
  }
  return 0.5 * area;
}

TEST(TrimmedSurface, HolesOfHermiteAndLagrangeCurvesAreMeasured) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  // A Hermite loop through four points of the circle of radius 0.2 about
  // (0.3, 0.3), clockwise, with the circle's tangents scaled by pi / 2.
  std::vector<double> points, tangents;
  for (int k = 0; k <= 4; ++k) {
    const double theta = -0.5 * kPi * k;
    points.insert(points.end(),
                  {0.3 + 0.2 * std::cos(theta), 0.3 + 0.2 * std::sin(theta)});
    tangents.insert(tangents.end(), {0.1 * kPi * std::sin(theta),
                                     -0.1 * kPi * std::cos(theta)});
  }
  const Curve hermite = *HermiteCurve::Create(
      {.points = {2, points}, .tangents = {2, tangents}, .nodes = {}});
  // Two Lagrange arcs (quartic, through five points each) making a
  // clockwise loop about (0.7, 0.7).
  std::vector<double> upper, lower;
  for (int k = 0; k <= 4; ++k) {
    const double a = kPi - 0.25 * kPi * k;  // pi down to 0: the upper half
    upper.insert(upper.end(),
                 {0.7 + 0.15 * std::cos(a), 0.7 + 0.1 * std::sin(a)});
    const double b = -0.25 * kPi * k;  // 0 down to -pi: the lower half
    lower.insert(lower.end(),
                 {0.7 + 0.15 * std::cos(b), 0.7 + 0.1 * std::sin(b)});
  }
  const Curve first =
      *LagrangeCurve::Create({.points = {2, upper}, .nodes = {}});
  const Curve second =
      *LagrangeCurve::Create({.points = {2, lower}, .nodes = {}});
  absl::StatusOr<TrimmedSurface> face = MakeFace(
      surface, std::nullopt, {TrimLoop{{hermite}}, TrimLoop{{first, second}}});
  ASSERT_TRUE(face.ok()) << face.status();
  absl::StatusOr<FaceAreaResult> area = FaceArea(*face, 1e-13);
  ASSERT_TRUE(area.ok()) << area.status();
  // The holes' areas by the shoelace formula on 2 x 10^5 samples: within
  // 1e-11 of the curves' (the chords cut off about L^3 kappa / 12 each).
  const double holes = ShoelaceArea(hermite, 200000) +
                       ShoelaceArea(first, 200000) +
                       ShoelaceArea(second, 200000);
  EXPECT_NEAR(area->area, 1.0 + holes, 1e-10);
  EXPECT_EQ(Where(*face, 0.3, 0.3, 1e-9), PointLocation::kOutside);
  EXPECT_EQ(Where(*face, 0.7, 0.7, 1e-9), PointLocation::kOutside);
  EXPECT_EQ(Where(*face, 0.7, 0.3, 1e-9), PointLocation::kInside);
}

TEST(TrimmedSurface, ASingleClosedBezierCurveIsALoop) {
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  // A teardrop: a cubic from (0.5, 0.3) back to itself, clockwise.
  const BezierCurveData drop{
      .dimension = 2,
      .coordinates = {0.5, 0.3, 0.1, 0.8, 0.9, 0.8, 0.5, 0.3},
      .weights = {}};
  const Curve teardrop = *BezierCurve::Create(drop.view());
  absl::StatusOr<TrimmedSurface> face =
      MakeFace(surface, std::nullopt, {TrimLoop{{teardrop}}});
  ASSERT_TRUE(face.ok()) << face.status();
  absl::StatusOr<FaceAreaResult> area = FaceArea(*face, 1e-13);
  ASSERT_TRUE(area.ok()) << area.status();
  EXPECT_NEAR(area->area, 1.0 + ShoelaceArea(teardrop, 200000), 1e-10);
  // A cubic whose control polygon crosses itself makes a curve that does
  // too (the loop of (0.2, 0.2), (1.2, 0.8), (-0.2, 0.8), (0.8, 0.2)),
  // closed by a segment.
  const BezierCurveData looped{
      .dimension = 2,
      .coordinates = {0.2, 0.2, 1.2, 0.8, -0.2, 0.8, 0.8, 0.2},
      .weights = {}};
  const BezierCurveData closing{
      .dimension = 2, .coordinates = {0.8, 0.2, 0.2, 0.2}, .weights = {}};
  const TrimLoop figure{{*BezierCurve::Create(looped.view()),
                         *BezierCurve::Create(closing.view())}};
  absl::StatusOr<TrimmedSurface> crossing = MakeFace(surface, figure, {});
  EXPECT_EQ(PathOf(crossing), "outer.curves[0]");
  EXPECT_NE(crossing.status().message().find("crosses itself"),
            std::string::npos)
      << crossing.status();
}

TEST(TrimmedSurface, RaysThroughVerticesCountOnce) {
  // An octagon, and points on the horizontal lines through its vertices
  // (the winding ray runs through a vertex of the polyline there).
  const SurfaceData plane = BilinearPlane();
  const Surface surface = *BezierSurface::Create(plane.bezier_view());
  const BSplineCurveData octagon =
      trim_testing::RegularPolygon(8, 0.4, 0.5, 0.5);
  absl::StatusOr<TrimmedSurface> face = MakeFace(surface, LoopOf(octagon), {});
  ASSERT_TRUE(face.ok()) << face.status();
  for (int k = 0; k < 8; ++k) {
    const double v = trim_testing::PolygonVertex(8, 0.4, 0.5, 0.5, k)[1];
    for (double u = 0.01; u < 1.0; u += 0.02) {
      // Inside a convex polygon: left of every edge.
      double nearest = INFINITY;
      for (int e = 0; e < 8; ++e) {
        const std::array<double, 2> a =
            trim_testing::PolygonVertex(8, 0.4, 0.5, 0.5, e);
        const std::array<double, 2> b =
            trim_testing::PolygonVertex(8, 0.4, 0.5, 0.5, e + 1);
        nearest = std::min(
            nearest, ((b[0] - a[0]) * (v - a[1]) - (b[1] - a[1]) * (u - a[0])) /
                         std::hypot(b[0] - a[0], b[1] - a[1]));
      }
      if (std::abs(nearest) < 1e-9) continue;
      EXPECT_EQ(Where(*face, u, v, 1e-12),
                nearest > 0 ? PointLocation::kInside : PointLocation::kOutside)
          << u << ", " << v;
    }
  }
}

}  // namespace
}  // namespace freeform
